"""Simulate a hybeam FMU with fmpy and write the history of every output (CSV) and a plot of
the tip deflection (PNG): vertical (y) for a planar scene, y and z for a spatial one (the FMU
has tip.position.z).

usage: simulate_fmu.py FMU [--stop T] [--step H] [--out PREFIX] [--view DIR]

--view DIR sets the FMU's String parameter visualization.directory: the FMU itself writes the
ParaView series of the beam's shape and, at fmi2Terminate, its animation page there
(docs/view.md).
"""

import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from fmpy import read_model_description, simulate_fmu  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fmu")
    ap.add_argument(
        "--stop", type=float, default=None, help="stop time [s] (default: DefaultExperiment)"
    )
    ap.add_argument(
        "--step",
        type=float,
        default=None,
        help="communication step [s] (default: DefaultExperiment)",
    )
    ap.add_argument("--out", default="tip", help="output prefix: PREFIX.csv and PREFIX.png")
    ap.add_argument(
        "--view", default=None, help="the FMU writes its ParaView series and page into DIR"
    )
    a = ap.parse_args()
    md = read_model_description(a.fmu)
    stop = a.stop or float(md.defaultExperiment.stopTime)
    step = a.step or float(md.defaultExperiment.stepSize)
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    start = {"visualization.directory": a.view} if a.view else {}
    res = simulate_fmu(
        a.fmu, stop_time=stop, output_interval=step, output=outputs, start_values=start
    )
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time"] + outputs)
        for row in res:
            w.writerow([repr(float(x)) for x in row])
    axes = ["y", "z"] if "tip.position.z" in outputs else ["y"]
    fig, ax = plt.subplots(figsize=(8, 4))
    lowest = []
    for axis in axes:
        d = res[f"tip.position.{axis}"] - res[f"tip.position.{axis}"][0]
        ax.plot(res["time"], 1e3 * d, label=f"tip {axis}")
        lowest.append(f"{axis} {1e3 * float(d.min()):.3f} mm")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("tip deflection [mm]" if len(axes) > 1 else "vertical tip deflection [mm]")
    ax.set_title(f"{md.modelName}: tip deflection (fmpy, step {step:g} s)")
    if len(axes) > 1:
        ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)
    print(
        f"{md.modelName}: {len(res)} samples to t = {res['time'][-1]:.3f} s; "
        f"lowest tip deflection {', '.join(lowest)}; wrote {a.out}.csv and {a.out}.png"
        + (f"; the FMU wrote its series and animation page into {a.view}/" if a.view else "")
    )


if __name__ == "__main__":
    main()
