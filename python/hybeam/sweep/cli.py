"""`hybeam-sweep`: parameter studies of a beam FMU (docs/sweeps.md).

    hybeam-sweep run STUDY.toml --out DIR [--scheduler tcp://HOST:PORT] [--workers N] [--serial]
    hybeam-sweep plot DIR

`run` runs every variant of the study (a Dask LocalCluster of all cores unless `--scheduler`
names a running one; `--serial`: in this process), skipping those DIR/variants.parquet already
holds (the same content hash), and writes DIR/variants.parquet (one row per variant: id,
parameters, summaries, status, message, wall_s), DIR/series.parquet (variant, time, the series)
and DIR/sweep.png. `plot` redraws DIR/sweep.png from the tables.
"""

import argparse
import dataclasses
import json
import pathlib
import sys

from .build import build
from .run import execute
from .study import SCENE, StudyError, load


def _table(study, done: dict, order: list[tuple[str, dict]]):
    """The variants table and the series table, rows in grid order."""
    import pandas as pd

    rows, series = [], []
    for vid, values in order:
        r = done.get(vid)
        if r is None:
            continue
        row = {"variant": vid, **values}
        row.update(r.get("summaries", {}))
        row.update(status=r["status"], message=r["message"], wall_s=r.get("wall_s", float("nan")))
        rows.append(row)
        if r["status"] == "ok" and "time" in r:
            part = pd.DataFrame({"variant": vid, "time": r["time"], **r["series"]})
            series.append(part)
    variants = pd.DataFrame(rows)
    ts = pd.concat(series, ignore_index=True) if series else pd.DataFrame()
    return variants, ts


def _previous(out: pathlib.Path, study) -> dict:
    """Results of an earlier run in `out`, by variant id (summaries, status, series)."""
    import pandas as pd

    vp, sp = out / "variants.parquet", out / "series.parquet"
    if not vp.exists():
        return {}
    v = pd.read_parquet(vp)
    s = pd.read_parquet(sp) if sp.exists() else pd.DataFrame(columns=["variant", "time"])
    done = {}
    for _, row in v.iterrows():
        part = s[s["variant"] == row["variant"]]
        done[row["variant"]] = {
            "status": row["status"],
            "message": row["message"],
            "wall_s": row["wall_s"],
            "summaries": {k: row[k] for k in study.summaries if k in v.columns},
            "time": part["time"].to_numpy(),
            "series": {c: part[c].to_numpy() for c in s.columns if c not in ("variant", "time")},
        }
    return done


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
    """DIR/sweep.png: each summary against each swept parameter (one point per variant)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    v = pd.read_parquet(out / "variants.parquet")
    meta = json.loads((out / "study.json").read_text())
    params, sums = meta["parameters"], meta["summaries"]
    ok = v[v["status"] == "ok"]
    fig, axes = plt.subplots(
        len(sums), len(params), figsize=(3.2 * len(params), 2.6 * len(sums)), squeeze=False
    )
    for i, s in enumerate(sums):
        for j, p in enumerate(params):
            ax = axes[i][j]
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
    values, `built` caching them by those values) and the build's error, if any."""
    if study.scene is None:
        return study, ""
    values = {k: variant[k] for k in study.parameters if k.startswith(SCENE)}
    key = json.dumps(values, sort_keys=True)
    if key not in built:
        fmu, error = build(study.scene, values, out / "fmus")
        sub = dataclasses.replace(study, fmu=fmu, parameters=study.fmu_parameters())
        built[key] = (sub, error)
    return built[key]


def run(study_path, out, scheduler=None, workers=None, serial=False, quiet=False):
    """Runs a study into `out` (see the module's docstring); returns the variants table."""
    study = load(study_path)
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    order, jobs, built, digests = [], {}, {}, {}
    for v in study.variants():
        sub, error = _study_of(study, v, out, built)
        if id(sub) not in digests:
            # the FMU's hash (its bytes read once per FMU, not per variant)
            digests[id(sub)] = error or sub.fmu_digest()
        vid = sub.variant_id(v, digests[id(sub)])
        order.append((vid, v))
        jobs.setdefault(id(sub), (sub, error, []))[2].append((vid, v))
    previous = _previous(out, study)
    # a structure whose FMU did not build: its variants are failed rows with the message
    for _, error, pairs in jobs.values():
        if error:
            previous.update({vid: {"status": "failed", "message": error} for vid, _ in pairs})
    todo = [
        (sub, [(vid, v) for vid, v in pairs if vid not in previous])
        for sub, error, pairs in jobs.values()
        if not error
    ]

    def progress(done, failed, total, elapsed):
        if quiet:
            return
        left = elapsed / done * (total - done) if done else float("nan")
        bar = "#" * round(30 * done / total)
        print(
            f"\r[{bar:<30}] {done}/{total} variants, {failed} failed, {elapsed:.0f} s, "
            f"~{left:.0f} s left",
            end="" if done < total else "\n",
            file=sys.stderr,
            flush=True,
        )

    n_todo = sum(len(t) for _, t in todo)
    if not quiet and n_todo < len(order):
        print(f"{len(order) - n_todo} variants already in {out}", file=sys.stderr)
    results = execute(todo, scheduler, workers, serial, progress)
    done = {**previous, **results}
    variants, series = _table(study, done, order)
    variants.to_parquet(out / "variants.parquet", index=False)
    series.to_parquet(out / "series.parquet", index=False)
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
    pl = sub.add_parser("plot", help="redraw DIR/sweep.png from the tables")
    pl.add_argument("out")
    a = p.parse_args(argv)
    try:
        if a.command == "run":
            v = run(a.study, a.out, a.scheduler, a.workers, a.serial)
            counts = v["status"].value_counts().to_dict() if len(v) else {}
            print(json.dumps({"variants": len(v), **counts, "out": str(a.out)}))
        else:
            plot(pathlib.Path(a.out))
    except StudyError as e:
        print(f"hybeam-sweep: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
