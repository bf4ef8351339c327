"""Simulate a hybeam FMU with fmpy and write the tip history (CSV) and a plot of the vertical
tip deflection (PNG).

usage: simulate_fmu.py FMU [--stop T] [--step H] [--out PREFIX]
"""

import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from fmpy import read_model_description, simulate_fmu  # noqa: E402

OUTPUTS = ["tip.position.x", "tip.position.y", "tip.velocity.x", "tip.velocity.y", "tip.angle",
           "root.force.x", "root.force.y", "root.moment.z",
           "energy.kinetic", "energy.strain", "energy.potential"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fmu")
    ap.add_argument("--stop", type=float, default=None, help="stop time [s] (default: DefaultExperiment)")
    ap.add_argument("--step", type=float, default=None, help="communication step [s] (default: DefaultExperiment)")
    ap.add_argument("--out", default="tip", help="output prefix: PREFIX.csv and PREFIX.png")
    a = ap.parse_args()
    md = read_model_description(a.fmu)
    stop = a.stop or float(md.defaultExperiment.stopTime)
    step = a.step or float(md.defaultExperiment.stepSize)
    res = simulate_fmu(a.fmu, stop_time=stop, output_interval=step, output=OUTPUTS)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time"] + OUTPUTS)
        for row in res:
            w.writerow([repr(float(x)) for x in row])
    y0 = res["tip.position.y"][0]
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(res["time"], 1e3 * (res["tip.position.y"] - y0))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("vertical tip deflection [mm]")
    ax.set_title(f"{md.modelName}: tip deflection (fmpy, step {step:g} s)")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)
    ymin = float((res["tip.position.y"] - y0).min())
    print(f"{md.modelName}: {len(res)} samples to t = {res['time'][-1]:.3f} s; "
          f"lowest tip deflection {1e3 * ymin:.3f} mm; wrote {a.out}.csv and {a.out}.png")


if __name__ == "__main__":
    main()
