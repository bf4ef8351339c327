"""`hybeam-fatigue`: the fatigue damage of a station's stress history (docs/fatigue.md).

    hybeam-fatigue RESULT --station NAME (--sn m=3,C=7.16e29[,cutoff=5.2e7] | --sn-file SN.toml)
                   [--column COLUMN] [--n-ref 2e6] [--plot PNG] [--json OUT.json]

RESULT is a run's CSV (`hybeam run`, an fmpy result) or a `hybeam-sweep` study directory
(its series.parquet: one damage per variant). The history is the column
`station.NAME.stress` unless `--column` names another (a signed normal stress keeps the
reversals that a von Mises stress folds). Prints the rainflow cycles' Miner damage, the
equivalent stress range at --n-ref cycles and the largest range; --plot draws the histogram
of the cycles (or, for a study, the damage per variant; the `plot` extra).
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .. import plotting
from .damage import Fatigue, FatigueError, SNCurve, assess, load_sn_file, parse_sn


def _curve(args: argparse.Namespace) -> SNCurve:
    if (args.sn is None) == (args.sn_file is None):
        raise FatigueError("give the S-N curve once: --sn m=3,C=... or --sn-file SN.toml")
    if args.sn is not None:
        return parse_sn(args.sn)
    path = pathlib.Path(args.sn_file)
    curves = load_sn_file(path)
    if args.station not in curves:
        raise FatigueError(
            f"{path}: no table [{args.station}]; it has {sorted(curves)}; add "
            f"[{args.station}] with m and C"
        )
    return curves[args.station]


def _read(path: pathlib.Path, read: Callable[[pathlib.Path], Any]) -> Any:
    """`read(path)`, a file that cannot be read or parsed a FatigueError naming it."""
    try:
        return read(path)
    except (OSError, ValueError) as e:
        raise FatigueError(f"{path}: cannot read it as a table ({e})") from None


def _histories(result: pathlib.Path, column: str) -> dict[str, np.ndarray]:
    """The history of `column` per run: {"": values} for a CSV, {variant: values} for a
    sweep directory."""
    import pandas as pd

    if result.is_dir():
        path = result / "series.parquet"
        if not path.exists():
            raise FatigueError(f"{result}: no series.parquet (a hybeam-sweep study directory?)")
        frame = _read(path, pd.read_parquet)
        have = [c for c in frame.columns if c not in ("variant", "time")]
        hint = "the study's series are", "add it to [outputs] series, or name another with --column"
    else:
        if not result.exists():
            raise FatigueError(f"{result}: no such file")
        path, frame = result, _read(result, pd.read_csv)
        have, hint = list(frame.columns), ("it has", "name another with --column")
    if column not in frame.columns:
        raise FatigueError(f"{path}: no column {column!r}; {hint[0]} {have} ({hint[1]})")
    if not pd.api.types.is_numeric_dtype(frame[column]):
        raise FatigueError(f"{path}: column {column!r} is not numeric; give a stress column [Pa]")
    if result.is_dir():
        return {str(v): g[column].to_numpy() for v, g in frame.groupby("variant", sort=False)}
    return {"": frame[column].to_numpy()}


def _figure(path: pathlib.Path, results: dict[str, Fatigue], title: str) -> None:
    plt = plotting.pyplot(f"the figure {path}")
    fig, ax = plt.subplots(figsize=(7, 4))
    if list(results) == [""]:
        c = results[""].cycles
        if len(c):
            ax.hist(c[:, 0] / 1e6, bins=40, weights=c[:, 1], color="#4a78b5")
        ax.set_xlabel("stress range [MPa]")
        ax.set_ylabel("cycles")
        ax.set_yscale("log")
    else:
        names = list(results)
        ax.bar(range(len(names)), [results[n].damage for n in names], color="#4a78b5")
        ax.set_xticks(range(len(names)), names, rotation=60, fontsize=7)
        ax.set_ylabel("Miner damage")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> int:
    """`hybeam-fatigue` (see the module's docstring); the exit code."""
    p = argparse.ArgumentParser(prog="hybeam-fatigue", description=(__doc__ or "").splitlines()[0])
    p.add_argument("result", help="a run's CSV or a hybeam-sweep study directory")
    p.add_argument("--station", required=True, help="the station's name")
    p.add_argument("--column", help="the stress column [Pa] (default station.NAME.stress)")
    p.add_argument("--sn", help="Basquin S-N curve m=..,C=..[,cutoff=..] (Pa)")
    p.add_argument("--sn-file", help="a TOML of S-N curves, a table per station")
    p.add_argument("--n-ref", type=float, default=2e6, help="cycles of the equivalent range")
    p.add_argument("--plot", help="the figure's path (PNG)")
    p.add_argument("--json", help="write the results as JSON here")
    args = p.parse_args(argv)
    try:
        sn = _curve(args)
        column = args.column or f"station.{args.station}.stress"
        histories = _histories(pathlib.Path(args.result), column)
        results = {k: assess(v, sn, args.n_ref) for k, v in histories.items()}
    except FatigueError as e:
        print(f"hybeam-fatigue: {e}", file=sys.stderr)
        return 2
    print(f"{args.result}: {column}, S-N m = {sn.m:g}, C = {sn.C:.4g}, cutoff = {sn.cutoff:.4g} Pa")
    print("| run | cycles | largest range [MPa] | equivalent range at n_ref [MPa] | damage |")
    print("|---|---|---|---|---|")
    for name, r in results.items():
        n = float(r.cycles[:, 1].sum()) if len(r.cycles) else 0.0
        print(
            f"| {name or args.result} | {n:g} | {r.largest_range / 1e6:.4g} | "
            f"{r.equivalent_range / 1e6:.4g} | {r.damage:.4e} |"
        )
    if args.json:
        out = {
            name or "run": {
                "damage": r.damage,
                "equivalent_range": r.equivalent_range,
                "n_ref": r.n_ref,
                "largest_range": r.largest_range,
                "cycles": r.cycles.tolist(),
            }
            for name, r in results.items()
        }
        pathlib.Path(args.json).write_text(json.dumps(out, indent=1))
    if args.plot:
        try:
            _figure(pathlib.Path(args.plot), results, f"{args.station}: {column}")
        except plotting.PlotUnavailable as e:
            print(f"hybeam-fatigue: {e}", file=sys.stderr)
            return 2
    return 0
