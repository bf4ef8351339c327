"""pytest options of the vehicle example: the car and boom FMUs (examples/vehicle/run.sh)."""

import pytest


def pytest_addoption(parser):
    parser.addoption("--car", default="out/car.fmu", help="car FMU")
    parser.addoption("--boom", default="out/boom.fmu", help="boom (beam) FMU")


@pytest.fixture(scope="session")
def fmus(request):
    return request.config.getoption("--car"), request.config.getoption("--boom")
