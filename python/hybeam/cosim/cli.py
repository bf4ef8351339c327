"""`hybeam-cosim SYSTEM --scheme NAME --step H`: couples the FMUs of a system file.

Writes DIR/cosim.csv and DIR/cosim.parquet (per communication point: time, the recorded
outputs, the step's iterations, its interface residual, the energy residual) and DIR/cosim.png,
and prints as its last line one JSON record: stable, energy_residual, energy_scale (J),
iterations (per step), wall_s, steps, scheme, step, t_end (reached), message.

--set FMU.KNOB=F scales the parameters a knob of the system file names by F (e.g.
boom.mass_factor=100 multiplies the boom's densities); --set FMU.PARAMETER=V sets a
String parameter to the text V (e.g. boom.visualization.directory=out/view) or a
parameter's start value.

Everything is checked before an FMU is instantiated (the system file, the options, the
variables named against the FMUs' modelDescription.xml); a bad input ends with one line naming
the field, the value and the fix, exit code 2. The FMUs' warnings are printed as they come
(once each); a run whose energy ledger saw too little energy exchanged to judge its stability
says "stability not judged" (exit code 0; "stable": null in the JSON record); NOT stable: exit
code 1.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import pathlib
import sys

from .master import Settings, run
from .subsystem import FmuError, FmuSubsystem
from .system import System, SystemFileError, Variables, _like, check, load, variables


def parameters(system: System, subs: dict[str, Variables | FmuSubsystem], sets: list[str]):
    """Start values per FMU: the system file's, then `--set` (knobs scale start values by a
    positive finite factor; a Real parameter takes a finite number, a String one the text).
    `subs`: each FMU's variables (`Variables`, or the instantiated `FmuSubsystem`)."""
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
        knobs = system.fmus[fmu].knobs
        if name not in knobs and not (var is not None and var.causality == "parameter"):
            names = sorted(knobs) + [n for n, v in s.vars.items() if v.causality == "parameter"]
            raise SystemFileError(
                f"--set {item!r}: {name!r} is neither a knob of {fmu} ({sorted(knobs)}) nor "
                f"one of its parameters{_like(name, names)}"
            )
        try:
            x = float(value)
        except ValueError:
            raise SystemFileError(f"--set {item!r}: {value!r} is not a number") from None
        if name in knobs:
            if not (math.isfinite(x) and x > 0):
                raise SystemFileError(
                    f"--set {item!r}: the knob {name} scales parameters of {fmu}; give a "
                    f"positive finite factor, e.g. {fmu}.{name}=10"
                )
            names = [v for p in knobs[name] for v in s.parameters(p)]
            if not names:
                raise SystemFileError(
                    f"--set {item!r}: knob {name} matches no parameter of "
                    f"{fmu} ({knobs[name]}); fix fmus.{fmu}.knobs.{name}"
                )
            for v in names:
                params[fmu][v] = x * float(params[fmu].get(v, s.vars[v].start))
        else:
            if not math.isfinite(x):
                raise SystemFileError(
                    f"--set {item!r}: {fmu}.{name} takes a finite number; give one, e.g. "
                    f"{fmu}.{name}={var.start if var.start is not None else 1.0}"
                )
            params[fmu][name] = x
    return params


def open_system(
    system: System, scheme: str, sets: list[str], on_warning=None
) -> dict[str, FmuSubsystem]:
    """Checks the system against its FMUs' model descriptions (`system.check`) and `sets`,
    then instantiates the FMUs and initializes them on the connections of `scheme` (see
    `system.py`); `on_warning(fmu, message)` gets the FMUs' warnings."""
    from .master import initialize

    system.scheme(scheme)
    models = variables(system)
    check(system, models)
    params = parameters(system, models, sets)
    subs = {}
    try:
        for n, f in system.fmus.items():
            subs[n] = FmuSubsystem(f.path, n, on_warning)
            subs[n].instantiate()
        initialize(system, scheme, subs, params)
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
    on_warning=None,
):
    """Opens the system's FMUs for `scheme` (`--set` items `sets`), runs it and closes them:
    the run's `Result`."""
    subs = open_system(system, scheme, list(sets), on_warning)
    try:
        return run(system, scheme, subs, step, t_end, settings)
    finally:
        for s in subs.values():
            s.close()


def _time(option: str, given, default: float, field: str) -> float:
    """A time [s] from `--option` (when given, 0 included) or the system file's `field`."""
    x = default if given is None else given
    where = option if given is not None else field
    if not math.isfinite(x) or not x > 0:
        raise SystemFileError(f"{where} = {x!r}: give a positive finite time [s]")
    return x


def _warnings():
    """An `on_warning` printing each distinct FMU warning once (to stderr)."""
    seen = set()

    def warn(fmu, message):
        if (fmu, message) not in seen:
            seen.add((fmu, message))
            print(f"hybeam-cosim: warning from {fmu}: {message}", file=sys.stderr, flush=True)

    return warn


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
        paths = {}
        for item in a.fmu:
            name, sep, path = item.partition("=")
            if not (sep and name and path):
                raise SystemFileError(
                    f"--fmu {item!r}: write NAME=PATH, e.g. --fmu boom=out/boom.fmu"
                )
            paths[name] = path
        system = load(a.system, paths)
        system.scheme(a.scheme)
        step = _time("--step", a.step, system.step, "system.step")
        t_end = _time("--t-end", a.t_end, system.t_end, "system.t_end")
        if step > t_end:
            raise SystemFileError(
                f"{'--step' if a.step is not None else 'system.step'} = {step!r}: longer than "
                f"--t-end = {t_end!r}; give a step of at most t_end"
            )
        n = round(t_end / step)
        if abs(n * step - t_end) > 1e-9 * max(t_end, 1.0):
            raise SystemFileError(
                f"--t-end = {t_end!r}: not a whole multiple of --step = {step!r}; give "
                f"--t-end {n * step:g} or a step that divides it"
            )
        settings = Settings(rtol=a.rtol, max_iterations=a.max_iterations)
        settings.check()
        res = simulate(system, a.scheme, step, t_end, a.set, settings, _warnings())
    except (SystemFileError, FmuError, ValueError) as e:
        print(f"hybeam-cosim: {e}", file=sys.stderr)
        raise SystemExit(2) from None
    out = pathlib.Path(a.out)
    write(
        res,
        out,
        f"{system.path.name}: {a.scheme}, h = {step:g} s",
        [] if a.no_plot else [f"{f}.{v}" for f, v in system.plot],
    )
    print(
        f"{len(res.rows)} points to {out / 'cosim.csv'}; {res.iterations:.2f} iterations "
        f"per step; {res.verdict}",
        file=sys.stderr,
    )
    print(json.dumps(res.summary(a.scheme, step)))
    return 1 if res.stable is False else 0


if __name__ == "__main__":
    sys.exit(main())
