"""`hybeam-sweep`: parameter studies of a beam FMU (docs/sweeps.md).

    hybeam-sweep run STUDY.toml --out DIR [--scheduler tcp://HOST:PORT] [--workers N] [--serial]
    hybeam-sweep plot DIR

`run` runs every variant of the study (a Dask LocalCluster of all cores unless `--scheduler`
names a running one; `--serial`: in this process), writing each chunk of variants to DIR/chunks/
as it completes and skipping the variants those chunks already hold (the same content hash: a
rerun of an interrupted sweep resumes it), then gathers DIR/variants.parquet (one row per
variant: id, parameters, summaries, status, message, wall_s), DIR/series.parquet (variant, time,
the series) and DIR/sweep.png. A study of more than `max_variants` variants ([study]
max_variants, `--max-variants`, default 100000) is refused before anything runs. `plot` redraws
DIR/sweep.png from the tables (sweep.png needs the `plot` extra: pip install
'hybeam-tools[plot]').

The command line only: the study runner is `hybeam.sweep.sweep.run`, the figure
`hybeam.sweep.plot.plot`.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys
from collections.abc import Sequence

from .. import plotting
from .plot import plot
from .study import MAX_VARIANTS, StudyError
from .sweep import run


def main(argv: Sequence[str] | None = None) -> int:
    """`hybeam-sweep run|plot` (see the module's docstring); the exit code."""
    p = argparse.ArgumentParser(prog="hybeam-sweep", description=(__doc__ or "").splitlines()[0])
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run a study")
    r.add_argument("study")
    r.add_argument("--out", required=True)
    r.add_argument("--scheduler", help="a running Dask scheduler, tcp://HOST:PORT")
    r.add_argument("--workers", type=int, help="LocalCluster worker processes (default: cores)")
    r.add_argument("--serial", action="store_true", help="run in this process, no Dask")
    r.add_argument(
        "--max-variants",
        type=int,
        help=f"the largest study run (default: [study] max_variants, else {MAX_VARIANTS})",
    )
    pl = sub.add_parser("plot", help="redraw DIR/sweep.png from the tables")
    pl.add_argument("out")
    a = p.parse_args(argv)
    try:
        if a.command == "run":
            if a.workers is not None and a.workers < 1:
                raise StudyError(f"--workers = {a.workers}: give at least 1 (or --serial)")
            v = run(a.study, a.out, a.scheduler, a.workers, a.serial, max_variants=a.max_variants)
            counts = v["status"].value_counts().to_dict() if len(v) else {}
            print(json.dumps({"variants": len(v), **counts, "out": str(a.out)}))
        else:
            plot(pathlib.Path(a.out))
    except (StudyError, plotting.PlotUnavailable) as e:
        print(f"hybeam-sweep: {e}", file=sys.stderr)
        raise SystemExit(2) from None
    except KeyboardInterrupt:
        print(
            f"\nhybeam-sweep: interrupted; the chunks that completed are kept in "
            f"{pathlib.Path(a.out) / 'chunks'}: rerun the same command to resume",
            file=sys.stderr,
        )
        raise SystemExit(130) from None
    return 0


if __name__ == "__main__":
    sys.exit(main())
