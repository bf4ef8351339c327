"""pytest options of the spatial vehicle example: the car and boom FMUs
(examples/vehicle3d/run.sh) and the planar pair of the symmetric comparison
(examples/vehicle/run.sh)."""

import pytest


def pytest_addoption(parser):
    parser.addoption("--car", default="out/car3d.fmu", help="spatial car FMU")
    parser.addoption("--boom", default="out/boom_3d.fmu", help="spatial boom (beam) FMU")
    parser.addoption("--planar-car", default="out/car.fmu", help="pitch-plane car FMU")
    parser.addoption("--planar-boom", default="out/boom.fmu", help="planar boom (beam) FMU")


@pytest.fixture(scope="session")
def fmus(request):
    return request.config.getoption("--car"), request.config.getoption("--boom")


@pytest.fixture(scope="session")
def planar_fmus(request):
    return request.config.getoption("--planar-car"), request.config.getoption("--planar-boom")
