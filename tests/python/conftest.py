"""pytest options for the FMU tests.

The FMU under test is given by ``--fmu PATH`` or the ``HYBEAM_FMU`` environment variable
(default: ``target/fmu/case1.fmu``). The tests rely only
on the variable names every beam FMU has: inputs ``tip.force.x``/``tip.force.y`` and
outputs ``tip.position.x``/``tip.position.y``. ``--huge-force`` (default 1e9 N) must make a
step fail (fmi2Discard).
"""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def pytest_addoption(parser):
    parser.addoption(
        "--fmu",
        default=os.environ.get("HYBEAM_FMU", str(ROOT / "target/fmu/case1.fmu")),
        help="FMU to test (default: $HYBEAM_FMU or target/fmu/case1.fmu)",
    )
    parser.addoption(
        "--huge-force",
        type=float,
        default=float(os.environ.get("HYBEAM_HUGE_FORCE", "1e9")),
        help="tip force [N] that makes a step fail",
    )


@pytest.fixture(scope="session")
def fmu_path(request):
    path = pathlib.Path(request.config.getoption("--fmu"))
    if not path.is_file():
        pytest.fail(
            f"FMU {path} not found: build it with "
            "`cargo fmu-build scenes/case1.toml --out target/fmu`"
        )
    return str(path)


@pytest.fixture(scope="session")
def huge_force(request):
    return request.config.getoption("--huge-force")
