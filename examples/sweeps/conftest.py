"""pytest options of the sweep example: the boom FMU (examples/sweeps/run.sh --test)."""

import pytest


def pytest_addoption(parser):
    parser.addoption("--boom", default="out/boom.fmu", help="boom (beam) FMU")


@pytest.fixture(scope="session")
def boom(request):
    return request.config.getoption("--boom")
