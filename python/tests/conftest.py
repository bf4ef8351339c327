"""Fixtures of the Python tools' tests: the roof boom's FMU for the tests that run one
(HYBEAM_BOOM_FMU, else out/boom.fmu, built by `cargo fmu-build scenes/boom.toml --out out
--platforms linux64` when missing, as examples/sweeps/run.sh does)."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def boom_fmu() -> pathlib.Path:
    given = os.environ.get("HYBEAM_BOOM_FMU")
    fmu = pathlib.Path(given) if given else ROOT / "out" / "boom.fmu"
    if not fmu.exists() and not given:
        cmd = ["cargo", "fmu-build", "scenes/boom.toml", "--out", "out", "--platforms", "linux64"]
        p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if p.returncode != 0:
            pytest.fail(f"{' '.join(cmd)} failed: {p.stderr[-2000:]}")
    if not fmu.exists():
        pytest.fail(
            f"{fmu} missing: cargo fmu-build scenes/boom.toml --out out --platforms linux64"
        )
    return fmu
