"""The results of a sweep on disk, written per chunk as chunks complete (DIR/chunks/): an
interrupted sweep keeps what ran, and a rerun of the same study skips every variant a chunk
file holds (by its content hash). At the end the chunks of the study's variants are gathered,
in grid order, into DIR/variants.parquet and DIR/series.parquet (the series streamed chunk by
chunk, pyarrow's ParquetWriter).

A chunk is two files named by the hash of its variant ids: `KEY.variants.parquet` (one row per
variant: id, parameters, summaries, status, message, wall_s) and `KEY.series.parquet`
(variant, time, the series; absent when no variant of the chunk ran). Each is written to a
temporary name and renamed, so a chunk file is whole or absent.
"""

import hashlib
import os
import pathlib
import sys

import numpy as np
import pandas as pd

from .study import Study

VARIANTS = ".variants.parquet"
SERIES = ".series.parquet"


def _atomic(frame: pd.DataFrame, path: pathlib.Path) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.part")
    frame.to_parquet(tmp, index=False)
    tmp.replace(path)


def import_legacy(out: pathlib.Path) -> None:
    """The tables of an earlier hybeam-sweep that wrote them only at the end (no chunks/) as
    one chunk, so that its variants are skipped as before."""
    chunks = out / "chunks"
    vp, sp = out / "variants.parquet", out / "series.parquet"
    if chunks.exists() or not vp.exists():
        return
    chunks.mkdir(parents=True)
    _atomic(pd.read_parquet(vp), chunks / f"legacy{VARIANTS}")
    if sp.exists():
        series = pd.read_parquet(sp)
        if len(series):
            _atomic(series, chunks / f"legacy{SERIES}")


def done_ids(out: pathlib.Path) -> set[str]:
    """The variant ids the chunk files of `out` hold."""
    import pyarrow.parquet as pq

    ids: set[str] = set()
    for f in sorted((out / "chunks").glob(f"*{VARIANTS}")):
        try:
            ids.update(pq.read_table(f, columns=["variant"]).column(0).to_pylist())
        except Exception as e:  # a file not written by us: rerun its variants
            print(f"hybeam-sweep: skipping unreadable {f} ({e})", file=sys.stderr)
    return ids


def write_chunk(
    out: pathlib.Path, study: Study, pairs: list[tuple[str, dict]], results: dict
) -> None:
    """Writes one chunk: `pairs` ((id, parameter values)) with their `results` by id."""
    chunks = out / "chunks"
    chunks.mkdir(parents=True, exist_ok=True)
    key = hashlib.sha256("\n".join(vid for vid, _ in pairs).encode()).hexdigest()[:16]
    rows, series = [], []
    for vid, values in pairs:
        r = results[vid]
        row = {"variant": vid, **values}
        got = r.get("summaries", {})
        row.update({k: got.get(k, float("nan")) for k in study.summaries})
        row.update(status=r["status"], message=r["message"], wall_s=r.get("wall_s", float("nan")))
        rows.append(row)
        if r["status"] == "ok" and "time" in r:
            part = {"variant": vid, "time": r["time"]}
            part.update({s: r["series"][s] for s in study.series})
            series.append(pd.DataFrame(part))
    if series:
        _atomic(pd.concat(series, ignore_index=True), chunks / f"{key}{SERIES}")
    # the variants file last: it is what marks the chunk done
    _atomic(pd.DataFrame(rows), chunks / f"{key}{VARIANTS}")


def gather(out: pathlib.Path, index: dict[str, int]) -> pd.DataFrame:
    """DIR/variants.parquet and DIR/series.parquet: the chunks' rows of the variants in
    `index` (id -> position in the grid), in grid order; returns the variants table."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    parts = []
    for f in sorted((out / "chunks").glob(f"*{VARIANTS}")):
        try:
            v = pd.read_parquet(f)
        except Exception:
            continue
        v = v[v["variant"].isin(index)]
        if len(v):
            parts.append((f, v))
    if parts:
        variants = pd.concat([v for _, v in parts], ignore_index=True)
        variants = variants.drop_duplicates("variant")
        order = variants["variant"].map(index).to_numpy()
        variants = variants.iloc[np.argsort(order, kind="stable")].reset_index(drop=True)
    else:
        variants = pd.DataFrame()
    _atomic(variants, out / "variants.parquet")
    # the series, a chunk at a time, the chunks in the grid order of their first variant
    parts.sort(key=lambda p: min(index[x] for x in p[1]["variant"]))
    tmp = out / f".series.parquet.{os.getpid()}.part"
    writer = None
    seen: set[str] = set()
    try:
        for f, v in parts:
            sf = f.with_name(f.name[: -len(VARIANTS)] + SERIES)
            if not sf.exists():
                continue
            s = pd.read_parquet(sf)
            s = s[s["variant"].isin(set(v["variant"]) - seen)]
            seen.update(v["variant"])
            if not len(s):
                continue
            pos = s["variant"].map(index).to_numpy()
            s = s.iloc[np.argsort(pos, kind="stable")].reset_index(drop=True)
            table = pa.Table.from_pandas(s, preserve_index=False)
            if writer is None:
                writer = pq.ParquetWriter(tmp, table.schema)
            writer.write_table(table.cast(writer.schema))
    finally:
        if writer is not None:
            writer.close()
    if writer is None:
        pd.DataFrame().to_parquet(tmp, index=False)
    tmp.replace(out / "series.parquet")
    return variants
