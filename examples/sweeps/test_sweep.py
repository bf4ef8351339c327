"""hybeam-sweep on the roof boom's FMU: a Dask LocalCluster of two workers gives the serial
results bit for bit, refused variants are data, a rerun skips what is done, fmi2Reset gives a
fresh instance's run, and the swept tip drop follows the closed form of a cantilever's step
response (docs/sweeps.md)."""

import math
import pathlib

import numpy as np
import pandas as pd
from hybeam.sweep import cli
from hybeam.sweep.run import run_chunk
from hybeam.sweep.study import load

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
    """12 variants, 4 with an inner diameter above the outer one (refused by the FMU): the
    same tables, bit for bit, serially and on a LocalCluster of 2 worker processes; the
    refused ones recorded with the FMU's message naming the field, the others complete."""
    study = _study(tmp_path, boom)
    serial = cli.run(study, tmp_path / "serial", serial=True, quiet=True)
    cluster = cli.run(study, tmp_path / "cluster", workers=2, quiet=True)
    assert len(serial) == 12
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
    v = cli.run(study, tmp_path / "out", workers=2, quiet=True)
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
    first = cli.run(study, tmp_path / "out", serial=True, quiet=True)
    again = cli.run(study, tmp_path / "out", serial=True, quiet=True)
    pd.testing.assert_frame_equal(first, again, check_exact=True)


def test_a_run_after_reset_is_a_fresh_instances_run(tmp_path, boom):
    """fmi2Reset between variants: a variant run after another in the same instance gives
    the bits of the same variant in a fresh instance."""
    study = load(_study(tmp_path, boom, lengths="[1.5]", walls="[0.044]"))
    a, b = study.variants()
    data, digest = study.fmu.read_bytes(), study.fmu_digest()
    fresh = run_chunk(data, digest, study, [("a", a)])[0][1]
    reused = run_chunk(data, digest, study, [("b", b), ("a", a), ("b", b)])
    for k in ("time",):
        assert np.array_equal(fresh[k], reused[1][1][k])
    for name, x in fresh["series"].items():
        assert np.array_equal(x, reused[1][1]["series"][name]), name
    assert fresh["summaries"] == reused[1][1]["summaries"]
    assert reused[0][1]["summaries"] == reused[2][1]["summaries"]
