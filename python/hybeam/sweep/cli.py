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
DIR/sweep.png from the tables.
"""

import argparse
import dataclasses
import json
import pathlib
import sys
import time

from .build import build
from .run import chunk_size, execute_chunks
from .store import done_ids, gather, import_legacy, write_chunk
from .study import MAX_VARIANTS, SCENE, StudyError, check, load, model_description


def sensitivity(variants, parameters: list[str], summaries: list[str]):
    """The sampled study's ranking: per summary, each parameter's Spearman rank correlation
    with it over the variants that ran (scipy.stats.spearmanr), strongest |rho| first."""
    import pandas as pd
    from scipy.stats import spearmanr

    ok = variants[variants["status"] == "ok"]
    rows = []
    for s in summaries:
        for p in parameters:
            rho = spearmanr(ok[p], ok[s]).statistic if len(ok) > 2 else float("nan")
            rows.append({"summary": s, "parameter": p, "spearman_rho": float(rho)})
    table = pd.DataFrame(rows)
    table["rank"] = (
        table.groupby("summary")["spearman_rho"]
        .transform(lambda r: r.abs().rank(ascending=False, method="first"))
        .astype(int)
    )
    return table.sort_values(["summary", "rank"], ignore_index=True)


def plot(out: pathlib.Path, study=None):
    """DIR/sweep.png: each summary against each swept parameter (one point per variant that
    ran)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    out = pathlib.Path(out)
    if not (out / "variants.parquet").exists() or not (out / "study.json").exists():
        raise StudyError(
            f"{out}: no sweep there (variants.parquet, study.json); run "
            f"hybeam-sweep run STUDY.toml --out {out} first"
        )
    v = pd.read_parquet(out / "variants.parquet")
    meta = json.loads((out / "study.json").read_text())
    params, sums = meta["parameters"], meta["summaries"]
    if not sums:
        raise StudyError(f"{out}: the study has no [outputs] summaries to plot; add some")
    ok = v[v["status"] == "ok"] if "status" in v else v.iloc[:0]
    fig, axes = plt.subplots(
        len(sums), len(params), figsize=(3.2 * len(params), 2.6 * len(sums)), squeeze=False
    )
    for i, s in enumerate(sums):
        for j, p in enumerate(params):
            ax = axes[i][j]
            if p in ok and s in ok:
                ax.plot(ok[p], ok[s], "o", ms=4)
            ax.set_xlabel(p)
            ax.set_ylabel(s)
            ax.grid(alpha=0.3)
    fig.suptitle(f"{meta['study']}: {len(ok)} of {len(v)} variants ran")
    fig.tight_layout()
    fig.savefig(out / "sweep.png", dpi=110)
    plt.close(fig)


def _study_of(study, variant: dict, out: pathlib.Path, built: dict):
    """The study that runs `variant` (its FMU: the study's, or the one built for its scene
    values, `built` caching them by those values, each checked against the study as it is
    built) and the build's error, if any."""
    if study.scene is None:
        return study, ""
    values = {k: variant[k] for k in study.parameters if k.startswith(SCENE)}
    key = json.dumps(values, sort_keys=True)
    if key not in built:
        fmu, error = build(study.scene, values, out / "fmus")
        sub = dataclasses.replace(study, fmu=fmu, parameters=study.fmu_parameters())
        if not error:
            where = f"[study] scene (built with {values})"
            check(sub, model_description(where, fmu, str(fmu)), fmu.name)
        built[key] = (sub, error)
    return built[key]


def run(
    study_path,
    out,
    scheduler=None,
    workers=None,
    serial=False,
    quiet=False,
    max_variants: int | None = None,
):
    """Runs a study into `out` (see the module's docstring); returns the variants table.

    The variants are made lazily, in chunks of `chunk_size` variants; each chunk's results
    are written to DIR/chunks/ as it completes, and the variants a chunk file holds are
    skipped (a rerun resumes an interrupted sweep). The tables are gathered at the end."""
    study = load(study_path, max_variants)
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    import_legacy(out)
    done = done_ids(out)
    total = study.count()
    size = chunk_size(total)
    index: dict[str, int] = {}
    counts = {"skipped": 0, "ran": 0, "failed": 0}
    t0 = time.perf_counter()

    def chunks():
        """(study with its FMU, [(id, values)]) of the variants not done, `size` at a time
        per FMU, made as the runner asks for them."""
        built, digests, open_ = {}, {}, {}
        for i, v in enumerate(study.variants()):
            sub, error = _study_of(study, v, out, built)
            if id(sub) not in digests:
                # the FMU's hash (its bytes read once per FMU, not per variant)
                digests[id(sub)] = error or sub.fmu_digest()
            vid = sub.variant_id(v, digests[id(sub)])
            index[vid] = i
            if vid in done:
                counts["skipped"] += 1
                continue
            if error:
                # a structure whose FMU did not build: a failed row with fmu-build's message
                done.add(vid)
                record(sub, [(vid, v)], {vid: {"status": "failed", "message": error}})
                continue
            todo = open_.setdefault(id(sub), (sub, []))[1]
            todo.append((vid, v))
            if len(todo) == size:
                yield sub, open_.pop(id(sub))[1]
        for sub, todo in open_.values():
            yield sub, todo

    def record(sub, chunk, results):
        write_chunk(out, sub, chunk, results)
        counts["ran"] += len(chunk)
        counts["failed"] += sum(r["status"] != "ok" for r in results.values())
        if quiet:
            return
        done_now = counts["ran"] + counts["skipped"]
        elapsed = time.perf_counter() - t0
        left = elapsed / counts["ran"] * (total - done_now)
        bar = "#" * round(30 * done_now / total)
        print(
            f"\r[{bar:<30}] {done_now}/{total} variants, {counts['failed']} failed, "
            f"{elapsed:.0f} s, ~{left:.0f} s left",
            end="" if done_now < total else "\n",
            file=sys.stderr,
            flush=True,
        )

    execute_chunks(chunks(), record, scheduler, workers, serial)
    if not quiet and counts["skipped"]:
        print(f"{counts['skipped']} variants already in {out / 'chunks'}", file=sys.stderr)
    variants = gather(out, index)
    meta = {
        "study": study.path.name,
        "parameters": list(study.parameters),
        "summaries": list(study.summaries),
    }
    (out / "study.json").write_text(json.dumps(meta, indent=1))
    if study.sample is not None and study.summaries:
        ranking = sensitivity(variants, list(study.parameters), list(study.summaries))
        ranking.to_parquet(out / "sensitivity.parquet", index=False)
        if not quiet:
            print(ranking.to_string(index=False), file=sys.stderr)
    if study.summaries:
        plot(out)
    return variants


def main(argv=None):
    p = argparse.ArgumentParser(prog="hybeam-sweep", description=__doc__.splitlines()[0])
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
    except StudyError as e:
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
