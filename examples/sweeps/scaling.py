"""The sweep's scaling on this machine (docs/sweeps.md): a 64-variant study of the roof boom
(4 free lengths x 4 walls x 4 densities, 0.5 s after the tip step load) run serially in this
process, then on a LocalCluster of 1 and of 2 worker processes; the wall times, the
per-variant overhead of the distribution, and what travels per variant (pickled bytes).

    .venv/bin/python examples/sweeps/scaling.py out/boom.fmu --out docs/report/sweep_scaling.md
"""

import argparse
import pathlib
import pickle
import tempfile
import time

from hybeam.sweep import sweep
from hybeam.sweep.run import run_chunk
from hybeam.sweep.study import load

STUDY = """
[study]
fmu = "{fmu}"
stop_time = 0.5
step = 1e-3
decimate = 10
[parameters]
"tip.length" = [1.5, 1.8, 2.1, 2.4]
"*.inner_diameter" = [0.038, 0.040, 0.042, 0.044]
"*.density" = [7850.0, 10000.0, 12500.0, 15700.0]
[inputs]
"tip.force.y" = -200.0
[outputs]
series = ["tip.position.y", "root.moment.z"]
summaries = {{ tip_drop = "range(tip.position.y)", peak_root_moment = "peak(root.moment.z)" }}
"""


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("fmu")
    p.add_argument("--out", required=True)
    a = p.parse_args()
    tmp = pathlib.Path(tempfile.mkdtemp())
    path = tmp / "scaling.toml"
    path.write_text(STUDY.format(fmu=pathlib.Path(a.fmu).resolve()))
    study = load(path)
    n = len(study.variants())
    walls = {}
    for name, kw in [
        ("serial (this process, no Dask)", {"serial": True}),
        ("LocalCluster, 1 worker", {"workers": 1}),
        ("LocalCluster, 2 workers", {"workers": 2}),
    ]:
        t0 = time.perf_counter()
        v = sweep.run(path, tmp / f"run{len(walls)}", quiet=True, **kw)
        walls[name] = time.perf_counter() - t0
        assert (v["status"] == "ok").all() and len(v) == n
        print(f"{name}: {walls[name]:.1f} s", flush=True)
    data, digest = study.fmu_bytes()
    variant = study.variants()[0]
    task = pickle.dumps((digest, study, [(study.variant_id(variant, digest), variant)]))
    result = pickle.dumps(run_chunk(data, digest, study, [("v", variant)]))
    serial, one, two = walls.values()
    lines = [
        f"Sweep scaling (`.venv/bin/python examples/sweeps/scaling.py {a.fmu} --out {a.out}`): "
        f"{n} variants of the roof boom, 0.5 s each, on this 2-core machine",
        "",
        "| run | wall [s] | per variant [s] |",
        "|---|---|---|",
    ]
    lines += [f"| {k} | {w:.1f} | {w / n:.3f} |" for k, w in walls.items()]
    lines += [
        "",
        f"- distribution overhead per variant (1 worker − serial) / {n}: "
        f"{(one - serial) / n * 1e3:.0f} ms; speed-up of 2 workers over 1: {one / two:.2f}",
        f"- shipped once per worker: the FMU, {study.fmu.stat().st_size / 1e6:.1f} MB; per "
        f"variant: its task {len(task)} bytes (pickled study and values), its result "
        f"{len(result)} bytes (summaries and the decimated series)",
    ]
    pathlib.Path(a.out).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
