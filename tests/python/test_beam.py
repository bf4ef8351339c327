"""Beam physics through fmpy: the FMU agrees with the in-process runner, a force step moves the
tip the right way, and a static tip force settles at the elastica (docs/references.md §4a)."""

import csv
import os
import pathlib
import subprocess
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUNNER = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "hybeam"


@pytest.fixture(scope="module")
def md(fmu_path):
    return read_model_description(fmu_path)


def test_simulate_fmu_matches_the_runner_to_1e_12(fmu_path, md, tmp_path):
    assert RUNNER.is_file(), "build the runner first: cargo build --release --bin hybeam"
    scene = tmp_path / "scene.toml"
    with zipfile.ZipFile(fmu_path) as z:
        scene.write_bytes(z.read("resources/scene.toml"))
    out = tmp_path / "runner.csv"
    subprocess.run(
        [
            str(RUNNER),
            "run",
            str(scene),
            "--out",
            str(out),
            "--t-end",
            "0.3",
            "--output-step",
            "1e-3",
            "--quiet",
        ],
        check=True,
    )
    with open(out) as f:
        rows = list(csv.DictReader(f))
    # every FMU output the runner writes (planar or spatial)
    OUTPUTS = [v.name for v in md.modelVariables if v.causality == "output" and v.name in rows[0]]
    assert "tip.position.x" in OUTPUTS and "energy.strain" in OUTPUTS, OUTPUTS
    res = simulate_fmu(fmu_path, stop_time=0.3, output_interval=1e-3, output=OUTPUTS)
    assert len(res) == len(rows)
    worst = 0.0
    for name in OUTPUTS:
        runner = np.array([float(r[name]) for r in rows])
        worst = max(worst, float(np.max(np.abs(res[name] - runner))))
    assert worst <= 1e-12, f"largest difference {worst:.3e}"


def test_force_step_moves_the_tip_the_right_way(fmu_path):
    t_step, f = (
        0.1,
        -0.002,
    )  # small enough for the flat strip (strip_3d) to stay within its modal range
    inp = np.array(
        [(0.0, 0.0, 0.0), (t_step, 0.0, 0.0), (t_step, 0.0, f), (0.4, 0.0, f)],
        dtype=[("time", "f8"), ("tip.force.x", "f8"), ("tip.force.y", "f8")],
    )
    kw = dict(stop_time=0.4, output_interval=1e-3, output=["tip.position.y", "root.force.y"])
    pushed = simulate_fmu(fmu_path, input=inp, **kw)
    free = simulate_fmu(fmu_path, **kw)
    dy = pushed["tip.position.y"] - free["tip.position.y"]
    before = pushed["time"] <= t_step
    assert np.all(dy[before] == 0.0)
    # a downward force pulls the tip down: the difference is mostly negative and its extreme
    # is negative and large compared with any overshoot
    after = pushed["time"] > t_step + 0.005
    assert dy[after].mean() < 0.0
    assert dy[after].min() < -5.0 * max(dy[after].max(), 0.0)


def test_static_tip_force_settles_at_the_elastica(fmu_path, md):
    names = {v.name for v in md.modelVariables}
    if md.modelName != "case2_ancf":
        pytest.skip("elastica check runs on the all-ANCF damped rod (case2_ancf)")
    # alpha = P L^2 / EI = 1 on the 2 mm steel rod, L = 0.4 m: v/L = 0.30172, u/L = 0.05643
    d, length, e = 0.002, 0.4, 2.1e11
    ei = e * np.pi * d**4 / 64.0
    p = ei / length**2
    assert "ancf.damping_time" in names
    inp = np.array(
        [(0.0, 0.0, -p), (3.0, 0.0, -p)],
        dtype=[("time", "f8"), ("tip.force.x", "f8"), ("tip.force.y", "f8")],
    )
    res = simulate_fmu(
        fmu_path,
        stop_time=3.0,
        output_interval=0.01,
        input=inp,
        start_values={"gravity.y": 0.0, "ancf.damping_time": 0.02},
        output=["tip.position.x", "tip.position.y"],
    )
    v = -res["tip.position.y"][-1] / length
    u = (length - res["tip.position.x"][-1]) / length
    assert abs(v - 0.30172) < 1e-3 and abs(u - 0.05643) < 1e-3, (v, u)
