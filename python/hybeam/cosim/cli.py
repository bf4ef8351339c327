"""`hybeam-cosim SYSTEM --scheme NAME --step H`: couples the FMUs of a system file.

Writes DIR/cosim.csv and DIR/cosim.parquet (per communication point: time, the recorded
outputs, the step's iterations, its interface residual, the energy residual) and DIR/cosim.png,
and prints as its last line one JSON record: stable, energy_residual, energy_scale (J),
iterations (per step), wall_s, steps, scheme, step, t_end (reached), message.

--set FMU.KNOB=F scales the parameters a knob of the system file names by F (e.g.
boom.mass_factor=100 multiplies the boom's densities); --set FMU.PARAMETER=V sets a
String parameter to the text V (e.g. boom.visualization.directory=out/view) or a
parameter's start value.
"""

from __future__ import annotations

import argparse
import csv
import json
import pathlib
import sys

from .master import Settings, run
from .subsystem import FmuSubsystem
from .system import System, SystemFileError, load


def parameters(system: System, subs: dict[str, FmuSubsystem], sets: list[str]):
    """Start values per FMU: the system file's, then `--set` (knobs scale start values)."""
    params = {n: dict(f.parameters) for n, f in system.fmus.items()}
    for item in sets:
        key, sep, value = item.partition("=")
        fmu, dot, name = key.partition(".")
        if not (sep and dot) or fmu not in subs:
            raise SystemFileError(
                f"--set {item!r}: write FMU.NAME=VALUE with FMU one of {sorted(subs)}"
            )
        s = subs[fmu]
        var = s.vars.get(name)
        if var is not None and var.type == "String" and var.causality == "parameter":
            params[fmu][name] = value  # a String parameter takes the text as it is
            continue
        try:
            x = float(value)
        except ValueError:
            raise SystemFileError(f"--set {item!r}: {value!r} is not a number") from None
        if name in system.fmus[fmu].knobs:
            names = [v for p in system.fmus[fmu].knobs[name] for v in s.parameters(p)]
            if not names:
                raise SystemFileError(
                    f"--set {item!r}: knob {name} matches no parameter of "
                    f"{fmu} ({system.fmus[fmu].knobs[name]})"
                )
            for v in names:
                params[fmu][v] = x * float(params[fmu].get(v, s.vars[v].start))
        elif name in s.vars and s.vars[name].causality == "parameter":
            params[fmu][name] = x
        else:
            knobs = sorted(system.fmus[fmu].knobs)
            raise SystemFileError(
                f"--set {item!r}: {name!r} is neither a knob of {fmu} "
                f"({knobs}) nor one of its parameters"
            )
    return params


def open_system(system: System, scheme: str, sets: list[str]) -> dict[str, FmuSubsystem]:
    """Instantiates the system's FMUs and initializes them on the connections of `scheme`
    (see `system.py`)."""
    from .master import initialize

    subs = {}
    try:
        for n, f in system.fmus.items():
            if not f.path.exists():
                raise SystemFileError(
                    f"fmus.{n}.path = {str(f.path)!r}: no such file; build "
                    f"it or pass --fmu {n}=PATH"
                )
            subs[n] = FmuSubsystem(f.path, n)
            subs[n].instantiate()
        initialize(system, scheme, subs, parameters(system, subs, sets))
    except BaseException:
        for s in subs.values():
            s.close()
        raise
    return subs


def simulate(
    system: System,
    scheme: str,
    step: float,
    t_end: float,
    sets=(),
    settings: Settings | None = None,
):
    """Opens the system's FMUs for `scheme` (`--set` items `sets`), runs it and closes them:
    the run's `Result`."""
    subs = open_system(system, scheme, list(sets))
    try:
        return run(system, scheme, subs, step, t_end, settings)
    finally:
        for s in subs.values():
            s.close()


def write(result, out: pathlib.Path, title: str, plot: list[str]):
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "cosim.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(result.columns)
        w.writerows(result.rows)
    import pandas as pd

    # the same table as Parquet (float64 columns, what pandas and Arrow readers take directly)
    pd.DataFrame(result.rows, columns=result.columns, dtype=float).to_parquet(
        out / "cosim.parquet", index=False
    )
    if not result.rows:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tab = result.table()
    n = len(plot) + 1
    fig, ax = plt.subplots(n, 1, figsize=(8, 1.9 * n + 1), sharex=True, squeeze=False)
    for a, name in zip(ax[:-1, 0], plot, strict=True):
        a.plot(tab[:, 0], tab[:, result.columns.index(name)])
        a.set_ylabel(name, fontsize=8)
    a = ax[-1, 0]
    a.plot(tab[:, 0], tab[:, -1], color="k")
    a.set_ylabel("energy residual [J]", fontsize=8)
    a.set_xlabel("time [s]")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "cosim.png", dpi=100)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(
        prog="hybeam-cosim",
        description=__doc__.splitlines()[0],
        epilog="\n".join(__doc__.splitlines()[2:]),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("system", help="system file (TOML) or OSP system structure (.xml)")
    p.add_argument("--scheme", default="implicit", help="a scheme of the system file")
    p.add_argument("--step", type=float, help="communication step [s] (default: the file's)")
    p.add_argument("--t-end", type=float, help="stop time [s] (default: the file's)")
    p.add_argument("--set", action="append", default=[], metavar="FMU.KEY=VALUE")
    p.add_argument(
        "--fmu", action="append", default=[], metavar="NAME=PATH", help="override an FMU's path"
    )
    p.add_argument("--out", default="out/cosim", help="directory for cosim.csv, .parquet and .png")
    p.add_argument("--rtol", type=float, default=Settings.rtol)
    p.add_argument("--max-iterations", type=int, default=Settings.max_iterations)
    p.add_argument("--no-plot", action="store_true")
    a = p.parse_args(argv)
    try:
        paths = dict(item.split("=", 1) for item in a.fmu)
        system = load(a.system, paths)
        step = a.step or system.step
        t_end = a.t_end or system.t_end
        if not step > 0 or not t_end > 0:
            raise SystemFileError(f"--step {step} / --t-end {t_end}: give positive times")
        system.scheme(a.scheme)
        settings = Settings(rtol=a.rtol, max_iterations=a.max_iterations)
        res = simulate(system, a.scheme, step, t_end, a.set, settings)
    except (SystemFileError, ValueError) as e:
        print(f"hybeam-cosim: {e}", file=sys.stderr)
        return 2
    out = pathlib.Path(a.out)
    write(
        res,
        out,
        f"{system.path.name}: {a.scheme}, h = {step:g} s",
        [] if a.no_plot else [f"{f}.{v}" for f, v in system.plot],
    )
    print(
        f"{len(res.rows)} points to {out / 'cosim.csv'}; {res.iterations:.2f} iterations "
        f"per step; {'stable' if res.stable else 'NOT stable: ' + res.message}",
        file=sys.stderr,
    )
    print(json.dumps(res.summary(a.scheme, step)))
    return 0 if res.stable else 1


if __name__ == "__main__":
    sys.exit(main())
