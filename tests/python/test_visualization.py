"""The String parameter ``visualization.directory`` from fmpy (pinned 0.3.32): simulate_fmu's
start_values set it like any other parameter, and the FMU itself writes the ParaView series
(``STEM.pvd`` of ``STEM_NNNNNN.vtu``) and the animation page (``STEM.html``), STEM = the
instance name (fmpy's: the modelIdentifier) sanitized."""

import xml.etree.ElementTree as ET

import numpy as np
from fmpy import read_model_description, simulate_fmu

POSITIONS = ["tip.position.x", "tip.position.y"]


def test_declared_as_a_fixed_string_parameter(fmu_path):
    md = read_model_description(fmu_path)
    v = {v.name: v for v in md.modelVariables}["visualization.directory"]
    assert v.type == "String" and v.causality == "parameter" and v.variability == "fixed"
    assert v.start == ""


def test_simulate_fmu_writes_the_series(fmu_path, tmp_path):
    views = tmp_path / "views"
    res = simulate_fmu(
        fmu_path,
        stop_time=0.5,
        output_interval=0.01,
        output=POSITIONS,
        start_values={"visualization.directory": str(views)},
    )
    plain = simulate_fmu(fmu_path, stop_time=0.5, output_interval=0.01, output=POSITIONS)
    for name in POSITIONS:
        assert np.array_equal(res[name], plain[name])
    (pvd,) = views.glob("*.pvd")
    pieces = ET.parse(pvd).getroot().findall("./Collection/DataSet")
    assert len(pieces) == len(res["time"]) == 51
    times = np.array([float(p.get("timestep")) for p in pieces])
    assert np.allclose(times, res["time"], rtol=0, atol=1e-12)
    for p in pieces:
        assert (views / p.get("file")).is_file()
    assert pvd.with_suffix(".html").is_file()


def test_an_unwritable_directory_only_warns(fmu_path, tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    res = simulate_fmu(
        fmu_path,
        stop_time=0.1,
        output_interval=0.01,
        output=POSITIONS,
        start_values={"visualization.directory": str(blocker / "views")},
    )
    plain = simulate_fmu(fmu_path, stop_time=0.1, output_interval=0.01, output=POSITIONS)
    for name in POSITIONS:
        assert np.array_equal(res[name], plain[name])
