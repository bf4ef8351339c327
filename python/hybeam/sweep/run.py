"""Running a study's variants: on a Dask cluster (a `LocalCluster` of all cores by default, or an
existing scheduler), or serially in this process, with the same results bit for bit.

The convention of fmpy's `parameter_variation.py`: the variants go in chunks, each chunk runs in
one FMU instance, `fmi2Reset` between variants (a fresh instance after a failed one); at most
two chunks per worker are in flight, the next made (lazily, from the grid) as one completes.
The FMU's bytes are shipped to the workers (scattered once), written to a file named by their
SHA-256 in the worker's temporary directory, not assumed on a shared disk. A variant the FMU
refuses is recorded with its message; a chunk whose worker dies is rerun once by the scheduler
(`retries=1`). Results are ordered by the grid, whatever ran where and when.
"""

import dataclasses
import logging
import math
import os
import pathlib
import tempfile
import time
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from .study import INPUT, Study, StudyError


def _fmu_file(data: bytes, digest: str) -> str:
    """The FMU's bytes as a file in this process's temporary directory (written once)."""
    d = pathlib.Path(tempfile.gettempdir()) / "hybeam-sweep"
    d.mkdir(exist_ok=True)
    p = d / f"{digest}.fmu"
    if not p.exists():
        tmp = p.with_suffix(f".{os.getpid()}.part")
        tmp.write_bytes(data)
        tmp.replace(p)
    return str(p)


def frequency(t: np.ndarray, x: np.ndarray) -> float:
    """The dominant frequency [Hz] of `x(t)`: its mean-crossings (times interpolated linearly)
    over the span between the first and the last; nan with fewer than three."""
    y = x - np.mean(x)
    i = np.nonzero(np.signbit(y[:-1]) != np.signbit(y[1:]))[0]
    if len(i) < 3:
        return float("nan")
    tc = t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])
    return float((len(tc) - 1) / (2.0 * (tc[-1] - tc[0])))


def settling(t: np.ndarray, x: np.ndarray, band: float = 0.02) -> float:
    """The settling time [s] of `x(t)`: the last time it is outside ±`band` of its total
    change around its final value (0 if never; the end time if it has not settled)."""
    change = abs(x[-1] - x[0]) or np.max(np.abs(x - x[-1])) or 1.0
    out = np.nonzero(np.abs(x - x[-1]) > band * change)[0]
    return (
        float(t[out[-1] + 1])
        if len(out) and out[-1] + 1 < len(t)
        else float(t[-1] * bool(len(out)))
    )


def _summary(kind: str, t: np.ndarray, x: np.ndarray) -> float:
    if kind == "frequency":
        return frequency(t, x)
    if kind == "settling":
        return settling(t, x)
    kinds: dict[str, Callable[[np.ndarray], Any]] = {
        "max": np.max,
        "min": np.min,
        "peak": lambda v: np.max(np.abs(v)),
        "range": np.ptp,
        "rms": lambda v: np.sqrt(np.mean(v * v)),
        "mean": np.mean,
        "final": lambda v: v[-1],
    }
    return float(kinds[kind](x))


def parameter_names(study: Study, names_of: Callable[[str], list[str]]) -> dict[str, list[str]]:
    """The FMU parameters each study parameter (a name or a glob) sets; raises StudyError for
    one that matches none. `names_of(pattern)` lists the FMU's parameters matching it."""
    out = {}
    for p in study.parameters:
        names = names_of(p)
        if not names:
            raise StudyError(
                f"[parameters] {p!r}: matches no parameter of "
                f"{study.fmu.name if study.fmu else 'the FMU'}; "
                f"write a parameter's name (docs/fmu-variables.md) or a glob such as '*.density'"
            )
        out[p] = names
    return out


def _run_one(sub: Any, study: Study, variant: dict[str, Any]) -> dict:
    """One variant in an instantiated (or reset) FMU: its summaries and decimated series."""
    from hybeam.cosim.subsystem import StepRefused

    fmu_study = dataclasses.replace(study, parameters=study.fmu_parameters())
    sets = parameter_names(fmu_study, sub.parameters)
    values = {n: variant[p] for p, names in sets.items() for n in names}
    probes = list(dict.fromkeys(study.series + [v for _, v in study.summaries.values()]))
    n = int(round(study.stop_time / study.step))
    rows = np.empty((n + 1, len(probes)))
    try:
        sub.enter_initialization(values)
        sub.exit_initialization()
        rows[0] = sub.get(probes)
        names = list(study.inputs)
        start = [sub.vars[i].start for i in names] if names else []
        start = [float(x) if x is not None else 0.0 for x in start]
        for k in range(n):
            t = k * study.step
            if names:
                # from t = 0 on the initialized state (a constant is a step of the inputs)
                signals = zip(names, study.inputs.values(), start, strict=True)
                sub.set(names, [s.at(t, x0, variant.get(INPUT + i)) for i, s, x0 in signals])
            sub.step(t, study.step)
            rows[k + 1] = sub.get(probes)
    except StepRefused as e:
        return {"status": "failed", "message": str(e)}
    except Exception as e:  # fmpy raises on fmi2Error from a setter or initialization
        return {"status": "failed", "message": sub.last_message() or str(e)}
    if not np.all(np.isfinite(rows)):
        return {"status": "failed", "message": "an output was not finite"}
    col = {p: rows[:, i] for i, p in enumerate(probes)}
    times = np.arange(n + 1) * study.step
    keep = list(range(0, n + 1, study.decimate))
    if keep[-1] != n:
        keep.append(n)
    return {
        "status": "ok",
        "message": "",
        "summaries": {k: _summary(kind, times, col[v]) for k, (kind, v) in study.summaries.items()},
        "time": np.array(keep, dtype=float) * study.step,
        "series": {s: col[s][keep] for s in study.series},
    }


def run_chunk(data: bytes, digest: str, study: Study, chunk: list[tuple[str, dict]]) -> list:
    """Runs `chunk` ((variant id, parameter values) pairs) in one FMU instance, reset between
    variants; returns (id, result) pairs."""
    from hybeam.cosim.subsystem import FmuSubsystem

    sub = FmuSubsystem(_fmu_file(data, digest), "beam")
    sub.instantiate()
    out = []
    try:
        for k, (vid, variant) in enumerate(chunk):
            t0 = time.perf_counter()
            if k:
                sub.reset()
            res = _run_one(sub, study, variant)
            res["wall_s"] = time.perf_counter() - t0
            out.append((vid, res))
            if res["status"] != "ok":
                # a refused variant may leave the instance in error: the next gets a fresh one
                sub.slave.freeInstance()
                sub.instantiate()
    finally:
        sub.slave.freeInstance()
    return out


def _chunks(items: list, size: int) -> list[list]:
    return [items[i : i + size] for i in range(0, len(items), size)]


def chunk_size(count: int) -> int:
    """Variants per chunk for a study of `count` variants: at least 32 chunks (work for every
    worker of a small cluster), at most 64 variants each (what an interruption may lose per
    worker). Fixed by the count alone, so a rerun makes the same chunks."""
    return max(1, min(64, math.ceil(count / 32)))


def execute_chunks(
    chunks: Iterable[tuple[Study, list[tuple[str, dict]]]],
    on_chunk: Callable[[Study, list[tuple[str, dict]], dict[str, dict]], None],
    scheduler: str | None = None,
    workers: int | None = None,
    serial: bool = False,
) -> None:
    """Runs `chunks` ((study with its FMU, [(id, values)]) pairs, consumed lazily) serially
    here, on `scheduler` (`tcp://HOST:PORT`) or on a new `LocalCluster` of `workers`
    processes (default: all cores), with at most two chunks per worker in flight;
    `on_chunk(study, chunk, results)` is called here as each completes (results by id)."""
    shipped: dict[str, tuple] = {}

    def fmu_of(study, client=None):
        key = str(study.fmu)
        if key not in shipped:
            data, digest = study.fmu_bytes()
            shipped[key] = (client.scatter(data, broadcast=True) if client else data, digest)
        return shipped[key]

    if serial:
        for study, chunk in chunks:
            data, digest = fmu_of(study)
            on_chunk(study, chunk, dict(run_chunk(data, digest, study, chunk)))
        return
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler:
        client = Client(scheduler)
    else:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            silence_logs=logging.WARNING,
        )
        client = Client(cluster)
    try:
        n_workers = max(1, len(client.scheduler_info().get("workers", {})))
        pending = iter(chunks)
        running = as_completed()
        what = {}

        def submit() -> bool:
            for study, chunk in pending:
                data, digest = fmu_of(study, client)
                f = client.submit(run_chunk, data, digest, study, chunk, retries=1, pure=False)
                what[f.key] = (study, chunk)
                running.add(f)
                return True
            return False

        for _ in range(2 * n_workers):
            if not submit():
                break
        for f in running:
            study, chunk = what.pop(f.key)
            on_chunk(study, chunk, dict(f.result()))
            submit()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def execute(
    jobs: list[tuple[Study, list[tuple[str, dict]]]],
    scheduler: str | None = None,
    workers: int | None = None,
    serial: bool = False,
    progress: Callable[[int, int, int, float], None] | None = None,
) -> dict[str, dict]:
    """Runs the variants of `jobs` ((study with its FMU, [(id, values)]) pairs) as
    `execute_chunks` does; `progress(done, failed, total, elapsed_s)` is called as chunks
    complete. Returns the results by variant id."""
    results: dict[str, dict] = {}
    total = sum(len(todo) for _, todo in jobs)
    t0 = time.perf_counter()

    def collect(study, chunk, pairs):
        results.update(pairs)
        if progress:
            failed = sum(r["status"] != "ok" for r in results.values())
            progress(len(results), failed, total, time.perf_counter() - t0)

    chunks = (
        (study, chunk)
        for study, todo in jobs
        for chunk in _chunks(todo, max(1, math.ceil(len(todo) / 8)))
    )
    execute_chunks(chunks, collect, scheduler, workers, serial)
    return results
