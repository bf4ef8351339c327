"""Running a study: every variant, in chunks written as they complete, a rerun resuming
where an interrupted one stopped; the tables gathered at the end (what `hybeam-sweep run`
calls; the command line itself is `cli.py`)."""

from __future__ import annotations

import dataclasses
import json
import pathlib
import sys
import time
from collections.abc import Iterator

import pandas as pd

from .. import plotting
from .build import build
from .plot import plot
from .run import chunk_size, execute_chunks
from .sensitivity import sensitivity
from .store import done_ids, gather, import_legacy, write_chunk
from .study import SCENE, Study, check, load, model_description


def _study_of(study: Study, variant: dict, out: pathlib.Path, built: dict) -> tuple[Study, str]:
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
    study_path: str | pathlib.Path,
    out: str | pathlib.Path,
    scheduler: str | None = None,
    workers: int | None = None,
    serial: bool = False,
    quiet: bool = False,
    max_variants: int | None = None,
) -> pd.DataFrame:
    """Runs a study into `out` (DIR/chunks/, DIR/variants.parquet, DIR/series.parquet,
    DIR/study.json, DIR/sensitivity.parquet for a sampled study, DIR/sweep.png: docs/sweeps.md);
    returns the variants table. Without matplotlib (the `plot` extra) sweep.png is left out
    with a note on stderr.

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

    def chunks() -> Iterator[tuple[Study, list[tuple[str, dict]]]]:
        """(study with its FMU, [(id, values)]) of the variants not done, `size` at a time
        per FMU, made as the runner asks for them."""
        built: dict = {}
        digests: dict[int, str] = {}
        open_: dict[int, tuple[Study, list[tuple[str, dict]]]] = {}
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

    def record(sub: Study, chunk: list[tuple[str, dict]], results: dict) -> None:
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
        if plotting.available():
            plot(out)
        else:
            print(
                f"hybeam-sweep: no {out / 'sweep.png'}: matplotlib is not installed; "
                f"{plotting.EXTRA}, then hybeam-sweep plot {out}",
                file=sys.stderr,
            )
    return variants
