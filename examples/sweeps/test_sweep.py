"""hybeam-sweep on the roof boom's FMU: a Dask LocalCluster of two workers gives the serial
results bit for bit, refused variants are data, a rerun skips what is done, fmi2Reset gives a
fresh instance's run, and the swept tip drop follows the closed form of a cantilever's step
response (docs/sweeps.md)."""

import math
import pathlib

import numpy as np
import pandas as pd
import pytest
from hybeam.sweep import build as build_module
from hybeam.sweep import sweep
from hybeam.sweep.run import run_chunk
from hybeam.sweep.study import StudyError, load

E, D = 2.1e11, 0.05  # Pa, m: scenes/boom.toml's tube
ROOT = 1.0  # m: the modal root segment's length
F = 200.0  # N: the step load at the tip


def _study(tmp_path, boom, lengths="[1.5, 2.5]", walls="[0.044, 0.040, 0.06]", stop=0.3):
    text = f"""
[study]
fmu = "{pathlib.Path(boom).resolve()}"
stop_time = {stop}
step = 1e-3
decimate = 10
[parameters]
"tip.length" = {lengths}
"*.inner_diameter" = {walls}
"*.density" = [7850.0, 15700.0]
[inputs]
"tip.force.y" = {-F}
[outputs]
series = ["tip.position.y", "root.moment.z"]
summaries = {{ tip_drop = "range(tip.position.y)", peak_root_moment = "peak(root.moment.z)" }}
"""
    p = tmp_path / "study.toml"
    p.write_text(text)
    return p


def test_a_cluster_of_two_workers_gives_the_serial_results_and_refusals_are_data(tmp_path, boom):
    """16 variants, 4 with an inner diameter above the outer one (refused by the FMU): the
    same tables, bit for bit, serially and on a LocalCluster of 2 worker processes; the
    refused ones recorded with the FMU's message naming the field, the others complete."""
    study = _study(tmp_path, boom, walls="[0.044, 0.042, 0.040, 0.06]")
    serial = sweep.run(study, tmp_path / "serial", serial=True, quiet=True)
    cluster = sweep.run(study, tmp_path / "cluster", workers=2, quiet=True)
    assert len(serial) == 16
    failed = serial[serial["status"] == "failed"]
    assert len(failed) == 4 and (failed["*.inner_diameter"] == 0.06).all()
    assert failed["message"].str.contains("inner_diameter").all(), failed["message"].iloc[0]
    pd.testing.assert_frame_equal(serial.drop(columns="wall_s"), cluster.drop(columns="wall_s"))
    s1 = pd.read_parquet(tmp_path / "serial" / "series.parquet")
    s2 = pd.read_parquet(tmp_path / "cluster" / "series.parquet")
    pd.testing.assert_frame_equal(s1, s2, check_exact=True)
    assert (tmp_path / "cluster" / "sweep.png").exists()


def test_the_tip_drop_is_twice_the_static_deflection(tmp_path, boom):
    """An undamped cantilever under a step load F at its tip swings to twice the static
    deflection F L^3 / (3 E I) (the first mode dominates; gravity's static state superposes;
    0.6 s: past the first peak of the slowest, 3.5 m and twice as dense, period 0.36 s):
    the swept tip drop of every length, wall and density within 2 %."""
    study = _study(tmp_path, boom, lengths="[1.5, 2.0, 2.5]", walls="[0.044, 0.040]", stop=0.6)
    v = sweep.run(study, tmp_path / "out", workers=2, quiet=True)
    assert (v["status"] == "ok").all(), v["message"].tolist()
    for _, row in v.iterrows():
        length = ROOT + row["tip.length"]
        inertia = math.pi / 64 * (D**4 - row["*.inner_diameter"] ** 4)
        expected = 2 * F * length**3 / (3 * E * inertia)
        err = row["tip_drop"] / expected - 1
        print(
            f"L = {length} m, wall {row['*.inner_diameter']}: {row['tip_drop']:.5f} m, {err:+.2%}"
        )
        assert abs(err) < 0.02


def test_a_rerun_skips_the_variants_done(tmp_path, boom):
    """A second run into the same directory finds every variant by its content hash and runs
    none (the recorded wall times come back unchanged)."""
    study = _study(tmp_path, boom, lengths="[1.5]", walls="[0.044]")
    first = sweep.run(study, tmp_path / "out", serial=True, quiet=True)
    again = sweep.run(study, tmp_path / "out", serial=True, quiet=True)
    pd.testing.assert_frame_equal(first, again, check_exact=True)


def test_a_run_after_reset_is_a_fresh_instances_run(tmp_path, boom):
    """fmi2Reset between variants: a variant run after another in the same instance gives
    the bits of the same variant in a fresh instance."""
    study = load(_study(tmp_path, boom, lengths="[1.5]", walls="[0.044]"))
    a, b = study.variants()
    data, digest = study.fmu_bytes()
    fresh = run_chunk(data, digest, study, [("a", a)])[0][1]
    reused = run_chunk(data, digest, study, [("b", b), ("a", a), ("b", b)])
    for k in ("time",):
        assert np.array_equal(fresh[k], reused[1][1][k])
    for name, x in fresh["series"].items():
        assert np.array_equal(x, reused[1][1]["series"][name]), name
    assert fresh["summaries"] == reused[1][1]["summaries"]
    assert reused[0][1]["summaries"] == reused[2][1]["summaries"]


def test_a_scheduler_and_workers_as_processes_survive_a_killed_worker(tmp_path, boom):
    """`dask scheduler` and two `dask worker` processes on localhost, the study given the
    scheduler's address (the FMU shipped to the workers): one worker is killed once the first
    results are in, and still every variant comes back, each equal bit for bit to its serial
    run."""
    import socket
    import subprocess
    import sys
    import time

    from hybeam.sweep.run import execute

    dask = str(pathlib.Path(sys.executable).parent / "dask")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    procs = [
        subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
            **quiet,
        )
    ]
    try:
        worker = [dask, "worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard"]
        procs += [subprocess.Popen(worker, **quiet) for _ in range(2)]
        from dask.distributed import Client

        with Client(address, timeout=60) as c:
            c.wait_for_workers(2, timeout=60)
        study = load(_study(tmp_path, boom, walls="[0.044, 0.040]", stop=0.2))
        digest = study.fmu_digest()
        todo = [(study.variant_id(v, digest), v) for v in study.variants()]
        killed = []

        def progress(done, failed, total, elapsed):
            if not killed and done >= 1:
                procs[1].kill()
                killed.append(done)

        t0 = time.perf_counter()
        remote = execute([(study, todo)], scheduler=address, progress=progress)
        print(f"{len(remote)} variants in {time.perf_counter() - t0:.1f} s, worker killed")
        assert killed and procs[1].wait(timeout=10) is not None
        serial = execute([(study, todo)], serial=True)
        assert set(remote) == set(serial) and len(remote) == len(todo)
        for vid, r in serial.items():
            assert r["status"] == remote[vid]["status"] == "ok"
            assert r["summaries"] == remote[vid]["summaries"]
            for name, x in r["series"].items():
                assert np.array_equal(x, remote[vid]["series"][name])
    finally:
        for p in procs:
            p.kill()
            p.wait(timeout=10)


def test_a_sobol_sample_follows_the_closed_form_and_ranks_length_first(tmp_path, boom):
    """A scrambled Sobol sample (8 points, seed 3) of the free length and the inner diameter:
    the same points on every load of the study, inside the ranges; every variant's tip drop
    within 2 % of 2 F L^3/(3EI); the Spearman ranking puts the length first for the tip drop
    (the drop goes as L^3: x2.7 over the range, against x1.5 for the wall)."""
    text = f"""
[study]
fmu = "{pathlib.Path(boom).resolve()}"
stop_time = 0.5
step = 1e-3
sample = {{ method = "sobol", n = 8, seed = 3 }}
[parameters]
"tip.length" = {{ range = [1.5, 2.5] }}
"*.inner_diameter" = {{ range = [0.040, 0.044] }}
[inputs]
"tip.force.y" = {-F}
[outputs]
summaries = {{ tip_drop = "range(tip.position.y)" }}
"""
    path = tmp_path / "sample.toml"
    path.write_text(text)
    assert list(load(path).variants()) == list(load(path).variants())
    v = sweep.run(path, tmp_path / "out", workers=2, quiet=True)
    assert len(v) == 8 and (v["status"] == "ok").all()
    assert v["tip.length"].between(1.5, 2.5).all()
    assert v["*.inner_diameter"].between(0.040, 0.044).all()
    for _, row in v.iterrows():
        inertia = math.pi / 64 * (D**4 - row["*.inner_diameter"] ** 4)
        expected = 2 * F * (ROOT + row["tip.length"]) ** 3 / (3 * E * inertia)
        assert abs(row["tip_drop"] / expected - 1) < 0.02, row
    ranking = pd.read_parquet(tmp_path / "out" / "sensitivity.parquet")
    print(ranking)
    first = ranking[(ranking["summary"] == "tip_drop") & (ranking["rank"] == 1)]
    assert first["parameter"].item() == "tip.length"


def test_a_bad_study_field_is_named_with_its_value_and_the_fix(tmp_path, boom):
    path = tmp_path / "bad.toml"
    path.write_text(
        f'[study]\nfmu = "{pathlib.Path(boom).resolve()}"\nstop_time = 0.1\nstep = 1e-3\n'
        'sample = { method = "random", n = 4 }\n[parameters]\n"tip.length" = { range = [1, 2] }\n'
    )
    with pytest.raises(StudyError, match=r"\[study\] sample = .*random.*sobol"):
        load(path)


def _one_variant(tmp_path, boom, name, inputs, stop=0.3, series='"tip.position.y"'):
    path = tmp_path / f"{name}.toml"
    path.write_text(
        f'[study]\nfmu = "{pathlib.Path(boom).resolve()}"\nstop_time = {stop}\nstep = 1e-3\n'
        f'[parameters]\n"tip.length" = [2.0]\n[inputs]\n{inputs}\n'
        f"[outputs]\nseries = [{series}]\n"
        'summaries = { drop = "range(tip.position.y)", force = "range(root.force.y)" }\n'
    )
    return sweep.run(path, tmp_path / name, serial=True, quiet=True)


def test_a_csv_input_holding_the_load_gives_the_constant_inputs_bits(tmp_path, boom):
    """The tip load as a CSV time series (two rows of -200 N) against the same constant: the
    same summaries and series, bit for bit."""
    (tmp_path / "load.csv").write_text(f"time,fy\n0,{-F}\n1,{-F}\n")
    a = _one_variant(tmp_path, boom, "constant", f'"tip.force.y" = {-F}')
    b = _one_variant(tmp_path, boom, "csv", '"tip.force.y" = { csv = "load.csv", column = "fy" }')
    assert (a["drop"] == b["drop"]).all() and (a["force"] == b["force"]).all()
    sa = pd.read_parquet(tmp_path / "constant" / "series.parquet").drop(columns="variant")
    sb = pd.read_parquet(tmp_path / "csv" / "series.parquet").drop(columns="variant")
    pd.testing.assert_frame_equal(sa, sb, check_exact=True)


def test_a_mount_shaken_by_sine_inputs_carries_the_boom_rigidly(tmp_path, boom):
    """The mount moved vertically by sine inputs (position, velocity, acceleration: 5 mm at
    1 Hz, far below the 3 m boom's first mode, 5.3 Hz): the root force swings by
    2 m A w^2 (the boom's 10.4 kg carried rigidly) within 10 % (measured +8.4 %: the first
    mode's quasi-static response, r^2/(1 - r^2) = 3.7 % at r = 0.19, and its free vibration
    set off by the start's jerk ride on it)."""
    a, f = 0.005, 1.0
    w = 2 * math.pi * f
    inputs = "\n".join(
        [
            f'"root.position.y" = {{ sine = {{ amplitude = {a}, frequency = {f} }} }}',
            f'"root.velocity.y" = {{ sine = {{ amplitude = {a * w}, frequency = {f}, '
            "phase = 90.0 } }",
            f'"root.acceleration.y" = {{ sine = {{ amplitude = {-a * w * w}, frequency = {f} }} }}',
        ]
    )
    v = _one_variant(tmp_path, boom, "shake", inputs, stop=1.0)
    assert (v["status"] == "ok").all(), v["message"].tolist()
    mass = 7850 * math.pi / 4 * (D**2 - 0.044**2) * 3.0
    expected = 2 * mass * a * w * w
    print(f"root force range {v['force'].item():.4f} N, rigid {expected:.4f} N")
    assert abs(v["force"].item() / expected - 1) < 0.1


def test_a_scene_study_builds_an_fmu_per_structure(tmp_path):
    """`[study] scene` with `scene:` values that change the structure (the tip segment's ANCF
    elements, 4 and 8) and an FMU parameter (the tip length, 2 values): two FMUs built (one
    per structure, cached: a rerun builds none), four variants; the tip drop converges in the
    elements towards 2 F L^3/(3EI) (4 and 8 elements within 2 %); a structure that does not
    build (0 elements) gives failed rows with fmu-build's message."""
    scene = build_module.ROOT / "scenes" / "boom.toml"
    path = tmp_path / "scene.toml"
    path.write_text(
        f'[study]\nscene = "{scene}"\nstop_time = 0.5\nstep = 1e-3\n'
        '[parameters]\n"scene:segments.tip.elements" = [4, 8, 0]\n"tip.length" = [1.5, 2.5]\n'
        f'[inputs]\n"tip.force.y" = {-F}\n'
        '[outputs]\nsummaries = { tip_drop = "range(tip.position.y)" }\n'
    )
    v = sweep.run(path, tmp_path / "out", workers=2, quiet=True)
    fmus = sorted((tmp_path / "out" / "fmus").glob("*/boom.fmu"))
    assert len(fmus) == 2 and len(v) == 6
    bad = v[v["scene:segments.tip.elements"] == 0]
    assert (bad["status"] == "failed").all() and bad["message"].str.contains("fmu-build").all()
    ok = v[v["status"] == "ok"]
    assert len(ok) == 4
    inertia = math.pi / 64 * (D**4 - 0.044**4)
    for _, row in ok.iterrows():
        expected = 2 * F * (ROOT + row["tip.length"]) ** 3 / (3 * E * inertia)
        assert abs(row["tip_drop"] / expected - 1) < 0.02, row
    stamps = [f.stat().st_mtime_ns for f in fmus]
    sweep.run(path, tmp_path / "out", serial=True, quiet=True)
    assert [f.stat().st_mtime_ns for f in fmus] == stamps


def test_the_tip_rings_at_the_cantilevers_first_frequency(tmp_path, boom):
    """The frequency summary of the tip after the step load (1.5 s) against the uniform
    cantilever's first frequency (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4)), 2.5 and 3.5 m, two
    walls: within 2 %."""
    path = tmp_path / "freq.toml"
    path.write_text(
        f'[study]\nfmu = "{pathlib.Path(boom).resolve()}"\nstop_time = 1.5\nstep = 1e-3\n'
        '[parameters]\n"tip.length" = [1.5, 2.5]\n"*.inner_diameter" = [0.044, 0.040]\n'
        f'[inputs]\n"tip.force.y" = {-F}\n'
        '[outputs]\nsummaries = { f1 = "frequency(tip.position.y)" }\n'
    )
    v = sweep.run(path, tmp_path / "out", workers=2, quiet=True)
    for _, row in v.iterrows():
        di = row["*.inner_diameter"]
        inertia, area = math.pi / 64 * (D**4 - di**4), math.pi / 4 * (D**2 - di**2)
        length = ROOT + row["tip.length"]
        f1 = 1.8751**2 / (2 * math.pi) * math.sqrt(E * inertia / (7850 * area * length**4))
        print(f"L = {length} m, inner diameter {di}: {row['f1']:.4f} Hz, closed form {f1:.4f} Hz")
        assert abs(row["f1"] / f1 - 1) < 0.02


def test_a_list_of_csv_files_is_a_dimension_of_the_grid(tmp_path, boom):
    """The tip load from one of two CSV files per variant (100 N and 200 N held): a column
    `input:tip.force.y` naming the file, and each tip drop within 2 % of 2 F L^3/(3EI) for its
    own load."""
    for f in (100, 200):
        (tmp_path / f"f{f}.csv").write_text(f"time,fy\n0,{-f}\n")
    path = tmp_path / "csvs.toml"
    path.write_text(
        f'[study]\nfmu = "{pathlib.Path(boom).resolve()}"\nstop_time = 0.3\nstep = 1e-3\n'
        '[parameters]\n"tip.length" = [1.5]\n'
        '[inputs]\n"tip.force.y" = { csv = ["f100.csv", "f200.csv"], column = "fy" }\n'
        '[outputs]\nsummaries = { tip_drop = "range(tip.position.y)" }\n'
    )
    v = sweep.run(path, tmp_path / "out", serial=True, quiet=True)
    assert list(v["input:tip.force.y"]) == ["f100.csv", "f200.csv"]
    inertia = math.pi / 64 * (D**4 - 0.044**4)
    for load_, drop in zip((100, 200), v["tip_drop"], strict=True):
        expected = 2 * load_ * 2.5**3 / (3 * E * inertia)
        assert abs(drop / expected - 1) < 0.02, (load_, drop, expected)


def test_an_interrupted_sweep_resumes_where_it_stopped(tmp_path, boom, monkeypatch):
    """Results are written per chunk: a sweep interrupted after two chunks keeps them
    (DIR/chunks/), a rerun of the same study runs only the other variants, and the tables it
    gathers equal an uninterrupted run's, series bit for bit."""
    from hybeam.sweep import run as run_module

    study = _study(tmp_path, boom, lengths="[1.5, 2.5]", walls="[0.044]", stop=0.05)
    real = run_module.run_chunk
    ran = []

    def counted(stop_after=None):
        def run_chunk(data, digest, st, chunk):
            if stop_after is not None and len(ran) == stop_after:
                raise KeyboardInterrupt
            ran.append(len(chunk))
            return real(data, digest, st, chunk)

        return run_chunk

    monkeypatch.setattr(run_module, "run_chunk", counted(stop_after=2))
    with pytest.raises(KeyboardInterrupt):
        sweep.run(study, tmp_path / "out", serial=True, quiet=True)
    kept = sum(ran)
    assert 1 <= kept < 4 and list((tmp_path / "out" / "chunks").glob("*.variants.parquet"))
    ran.clear()
    monkeypatch.setattr(run_module, "run_chunk", counted())
    resumed = sweep.run(study, tmp_path / "out", serial=True, quiet=True)
    assert sum(ran) == 4 - kept
    whole = sweep.run(study, tmp_path / "whole", serial=True, quiet=True)
    assert (resumed["status"] == "ok").all(), resumed["message"].tolist()
    pd.testing.assert_frame_equal(resumed.drop(columns="wall_s"), whole.drop(columns="wall_s"))
    s1 = pd.read_parquet(tmp_path / "out" / "series.parquet")
    s2 = pd.read_parquet(tmp_path / "whole" / "series.parquet")
    pd.testing.assert_frame_equal(s1, s2, check_exact=True)


def test_the_study_is_checked_against_the_fmus_variables(tmp_path, boom):
    """A misspelt parameter, an unknown input and an unknown output are refused from the
    FMU's modelDescription.xml before anything runs, each with the closest name."""
    study = _study(tmp_path, boom, lengths="[1.5]", walls="[0.044]")
    text = study.read_text()
    for old, new, pattern in [
        ('"tip.length" =', '"tip.lenght" =', r"\[parameters\] 'tip.lenght'.*'tip.length'"),
        ('"tip.force.y" =', '"tip.force.q" =', r"\[inputs\] 'tip.force.q'.*'tip.force.y'"),
        ('"root.moment.z"]', '"root.momnt.z"]', r"\[outputs\] series.*'root.moment.z'"),
    ]:
        study.write_text(text.replace(old, new, 1))
        with pytest.raises(StudyError, match=pattern):
            sweep.run(study, tmp_path / "out", serial=True, quiet=True)
        assert not (tmp_path / "out").exists()
