"""`hybeam-cosim SYSTEM --scheme NAME --step H`: couples the FMUs of a system file.

SYSTEM: a system file (TOML), an SSP 1.0 system (`.ssp` archive or bare `.ssd`; see
docs/coupling.md for what the SSP carries and what stays in TOML) or an OSP system structure
(`.xml`).

Writes DIR/cosim.csv and DIR/cosim.parquet (per communication point: time, the recorded
outputs, the step's iterations, its interface residual, the energy residual) and DIR/cosim.png
(needs the `plot` extra: pip install 'hybeam-tools[plot]'; --no-plot draws the energy residual
alone, or nothing without matplotlib), and prints as its last line one JSON record: stable,
energy_residual, energy_scale (J), iterations (per step), wall_s, steps, scheme, step, t_end
(reached), message.

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

The command lines only: the runner is `hybeam.cosim.run` (parameters, open_system, simulate,
write), the studies `hybeam.cosim.stability`, the SSP export `hybeam.cosim.ssp`.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys
from collections.abc import Sequence

from .. import plotting
from . import ssp, stability
from .master import Settings
from .run import OnWarning, simulate, write
from .subsystem import FmuError
from .system import SystemFileError, load


def _time(option: str, given: float | None, default: float, field: str) -> float:
    """A time [s] from `--option` (when given, 0 included) or the system file's `field`."""
    x = default if given is None else given
    where = option if given is not None else field
    if not math.isfinite(x) or not x > 0:
        raise SystemFileError(f"{where} = {x!r}: give a positive finite time [s]")
    return x


def _warnings() -> OnWarning:
    """An `on_warning` printing each distinct FMU warning once (to stderr)."""
    seen = set()

    def warn(fmu: str, message: str) -> None:
        if (fmu, message) not in seen:
            seen.add((fmu, message))
            print(f"hybeam-cosim: warning from {fmu}: {message}", file=sys.stderr, flush=True)

    return warn


def _paths(items: list[str]) -> dict[str, str]:
    """`--fmu NAME=PATH` items."""
    paths = {}
    for item in items:
        name, sep, path = item.partition("=")
        if not (sep and name and path):
            raise SystemFileError(f"--fmu {item!r}: write NAME=PATH, e.g. --fmu boom=out/boom.fmu")
        paths[name] = path
    return paths


def main(argv: Sequence[str] | None = None) -> int:
    """`hybeam-cosim` (see the module's docstring); the exit code."""
    doc = __doc__ or ""
    p = argparse.ArgumentParser(
        prog="hybeam-cosim",
        description=doc.splitlines()[0],
        epilog="\n".join(doc.splitlines()[2:]),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "system", help="system file (TOML), SSP system (.ssp, .ssd) or OSP system structure (.xml)"
    )
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
    figure = True
    try:
        if not plotting.available():
            if not a.no_plot:
                raise plotting.PlotUnavailable(
                    f"cosim.png needs matplotlib: {plotting.EXTRA}, or pass --no-plot"
                )
            figure = False
        system = load(a.system, _paths(a.fmu))
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
    except (SystemFileError, FmuError, ValueError, plotting.PlotUnavailable) as e:
        print(f"hybeam-cosim: {e}", file=sys.stderr)
        raise SystemExit(2) from None
    out = pathlib.Path(a.out)
    write(
        res,
        out,
        f"{system.path.name}: {a.scheme}, h = {step:g} s",
        [] if a.no_plot else [f"{f}.{v}" for f, v in system.plot],
        figure,
    )
    print(
        f"{len(res.rows)} points to {out / 'cosim.csv'}; {res.iterations:.2f} iterations "
        f"per step; {res.verdict}",
        file=sys.stderr,
    )
    print(json.dumps(res.summary(a.scheme, step)))
    return 1 if res.stable is False else 0


def study(argv: Sequence[str] | None = None) -> int:
    """`hybeam-cosim-study map|order` (`hybeam.cosim.stability`'s docstring); the exit code."""
    doc = stability.__doc__ or ""
    p = argparse.ArgumentParser(
        prog="hybeam-cosim-study",
        description=doc.splitlines()[0],
        epilog=doc,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = p.add_subparsers(dest="study", required=True)
    m = sub.add_parser("map", help="stability map")
    m.add_argument("system")
    m.add_argument("--scheme", action="append", required=True)
    m.add_argument("--steps", required=True, help="communication steps [s], comma separated")
    m.add_argument("--grid", required=True, metavar="FMU.KEY=V1,V2,...")
    m.add_argument("--out", default="out/coupling_map")
    o = sub.add_parser("order", help="order of convergence in the communication step")
    o.add_argument("system")
    o.add_argument("--scheme", required=True)
    o.add_argument("--steps", required=True)
    o.add_argument("--reference", type=float, required=True)
    o.add_argument("--columns", required=True)
    o.add_argument("--out")
    for x in (m, o):
        x.add_argument("--t-end", type=float, default=2.0)
        x.add_argument("--set", action="append", default=[])
        x.add_argument("--fmu", action="append", default=[])
        x.add_argument("--jobs", type=int, default=2)
    a = p.parse_args(argv)
    command = " ".join(sys.argv[1:] if argv is None else argv)
    try:
        fmus = _paths(a.fmu)
    except SystemFileError as e:
        print(f"hybeam-cosim-study: {e}", file=sys.stderr)
        raise SystemExit(2) from None
    common = dict(t_end=a.t_end, sets=a.set, fmus=fmus, jobs=a.jobs, command=command)
    if a.study == "map":
        stability.stability_map(
            a.system, a.scheme, stability.floats(a.steps), a.grid, a.out, **common
        )
    else:
        stability.order(
            a.system,
            a.scheme,
            stability.floats(a.steps),
            a.reference,
            a.columns.split(","),
            a.out,
            **common,
        )
    return 0


def export(argv: Sequence[str] | None = None) -> int:
    """`hybeam-ssp SYSTEM.toml --out NAME.ssd|NAME.ssp` (`hybeam.cosim.ssp`); the exit code."""
    doc = ssp.__doc__ or ""
    p = argparse.ArgumentParser(
        prog="hybeam-ssp",
        description="writes a system file (TOML) as an SSP 1.0 system: a bare .ssd (the FMUs "
        "referenced by relative path) or a .ssp archive (the FMUs packed into resources/)",
        epilog=doc,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("system", help="system file (TOML)")
    p.add_argument("--scheme", default="implicit", help="the scheme whose connections it holds")
    p.add_argument("--out", required=True, help="NAME.ssd or NAME.ssp")
    p.add_argument(
        "--fmu", action="append", default=[], metavar="NAME=PATH", help="override an FMU's path"
    )
    a = p.parse_args(argv)
    try:
        out = ssp.export(load(a.system, _paths(a.fmu)), a.scheme, pathlib.Path(a.out))
    except (SystemFileError, OSError) as e:
        print(f"hybeam-ssp: {e}", file=sys.stderr)
        raise SystemExit(2) from None
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
