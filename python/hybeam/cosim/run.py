"""Running a system: its start values (with `--set` items), its FMUs opened and initialized,
a run, and its tables and figure (what `hybeam-cosim` and the studies call; the command line
itself is `cli.py`)."""

from __future__ import annotations

import csv
import math
import pathlib
from collections.abc import Callable, Iterable, Mapping

from ..plotting import pyplot
from .master import Result, Settings, initialize, run
from .subsystem import FmuSubsystem, Subsystem
from .system import System, SystemFileError, Variables, _like, check, variables

#: `on_warning(fmu, message)`: gets the FMUs' warnings
OnWarning = Callable[[str, str], None]


def parameters(
    system: System, subs: Mapping[str, Variables | FmuSubsystem], sets: Iterable[str]
) -> dict[str, dict[str, float | str]]:
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
                start = var.start if var is not None and var.start is not None else 1.0
                raise SystemFileError(
                    f"--set {item!r}: {fmu}.{name} takes a finite number; give one, e.g. "
                    f"{fmu}.{name}={start}"
                )
            params[fmu][name] = x
    return params


def open_system(
    system: System, scheme: str, sets: Iterable[str], on_warning: OnWarning | None = None
) -> dict[str, Subsystem]:
    """Checks the system against its FMUs' model descriptions (`system.check`) and `sets`,
    then instantiates the FMUs and initializes them on the connections of `scheme` (see
    `system.py`); `on_warning(fmu, message)` gets the FMUs' warnings. The FMU subsystems by
    name (`FmuSubsystem`s; close them, or use `simulate`)."""
    system.scheme(scheme)
    models = variables(system)
    check(system, models)
    params = parameters(system, models, sets)
    subs: dict[str, Subsystem] = {}
    try:
        for n, f in system.fmus.items():
            fmu = FmuSubsystem(str(f.path), n, on_warning)
            subs[n] = fmu
            fmu.instantiate()
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
    sets: Iterable[str] = (),
    settings: Settings | None = None,
    on_warning: OnWarning | None = None,
) -> Result:
    """Opens the system's FMUs for `scheme` (`--set` items `sets`), runs it and closes them:
    the run's `Result`."""
    subs = open_system(system, scheme, list(sets), on_warning)
    try:
        return run(system, scheme, subs, step, t_end, settings)
    finally:
        for s in subs.values():
            s.close()


def write(
    result: Result, out: pathlib.Path, title: str, plot: list[str], figure: bool = True
) -> None:
    """DIR/cosim.csv and DIR/cosim.parquet (the same table), and unless `figure` is False
    DIR/cosim.png (the `plot` columns and the energy residual against time; needs the `plot`
    extra, see `plotting.py`)."""
    out = pathlib.Path(out)
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
    if figure and result.rows:
        draw(result, out / "cosim.png", title, plot)


def draw(result: Result, path: pathlib.Path, title: str, plot: list[str]) -> None:
    """The figure of a run: each of the `plot` columns and the energy residual against time
    (`plotting.PlotUnavailable` without matplotlib)."""
    plt = pyplot(f"{path.name} (the run's figure)")
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
    fig.savefig(path, dpi=100)
    plt.close(fig)
