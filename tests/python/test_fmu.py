"""fmpy (pinned 0.3.32) against the hybeam FMU: validation, simulation with inputs, rollback
with FMU state get/set/serialize, and fmi2Discard handling."""

import shutil
import subprocess
import sys

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2Discard, fmi2Error, fmi2LastSuccessfulTime, fmi2Terminated
from fmpy.validation import validate_fmu

FORCES = ["tip.force.x", "tip.force.y"]
POSITIONS = ["tip.position.x", "tip.position.y"]


@pytest.fixture(scope="module")
def md(fmu_path):
    return read_model_description(fmu_path)


@pytest.fixture(scope="module")
def vrs(md):
    return {v.name: v.valueReference for v in md.modelVariables}


@pytest.fixture()
def slave(fmu_path, md):
    """A low-level FMU2Slave, instantiated and initialized at t = 0."""
    unzipdir = extract(fmu_path)
    s = FMU2Slave(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="test",
    )
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    yield s
    s.freeInstance()
    shutil.rmtree(unzipdir, ignore_errors=True)


def test_fmpy_validate_reports_nothing(fmu_path):
    assert validate_fmu(fmu_path) == []
    cli = subprocess.run(
        [sys.executable, "-m", "fmpy", "validate", fmu_path], capture_output=True, text=True
    )
    assert cli.returncode == 0, cli.stdout + cli.stderr
    assert "No problems found" in cli.stdout


def test_variables_the_beam_shares(md):
    by_name = {v.name: v for v in md.modelVariables}
    for name in FORCES:
        assert by_name[name].causality == "input" and by_name[name].unit == "N"
    for name in POSITIONS:
        assert by_name[name].causality == "output" and by_name[name].unit == "m"
    assert md.coSimulation.canGetAndSetFMUstate and md.coSimulation.canSerializeFMUstate


def test_simulate_with_input_array(fmu_path):
    # forces within the beam's small-deformation range (Case 1 rod: PL²/EI = 1 at about 1 N)
    inp = np.array(
        [(0.0, 0.0, 0.0), (0.5, 0.0, 0.0), (0.5, 0.05, -0.02), (1.0, 0.05, -0.02)],
        dtype=[("time", "f8"), ("tip.force.x", "f8"), ("tip.force.y", "f8")],
    )
    res = simulate_fmu(fmu_path, stop_time=1.0, output_interval=0.01, input=inp, output=POSITIONS)
    free = simulate_fmu(fmu_path, stop_time=1.0, output_interval=0.01, output=POSITIONS)
    assert res["time"][0] == 0.0 and abs(res["time"][-1] - 1.0) < 1e-12
    for name in POSITIONS:
        assert np.all(np.isfinite(res[name]))
    before = res["time"] <= 0.5
    after = res["time"] > 0.6
    # Identical while the input is zero, different once the force acts.
    assert np.array_equal(
        res["tip.position.x"][before], free["tip.position.x"][free["time"] <= 0.5]
    )
    # (a heavy boom moves little under 0.05 N: the runs are deterministic, so any difference
    # beyond rounding is the force's; the 3 m sprayer arm's tip moves by ~3e-7 m along x)
    moved = max(
        np.max(np.abs(res[n][after] - free[n][free["time"] > 0.6]))
        for n in ("tip.position.x", "tip.position.y")
    )
    assert moved > 1e-9, moved


def test_rollback_with_fmu_state_reproduces_outputs(slave, vrs, fmu_path, md):
    out = [vrs[n] for n in POSITIONS]
    f = [vrs[n] for n in FORCES]
    h = 0.01

    def steps(s, k0, n):
        rows = []
        for k in range(k0, k0 + n):
            s.setReal(f, [0.01 * np.sin(0.1 * k), 0.02])
            s.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
            rows.append(s.getReal(out))
        return rows

    steps(slave, 0, 20)
    state = slave.getFMUstate()
    first = steps(slave, 20, 30)
    slave.setFMUstate(state)
    assert steps(slave, 20, 30) == first  # bit for bit (Python floats compare exactly)

    # Serialized state into a fresh instance of the same FMU.
    blob = slave.serializeFMUstate(state)
    unzipdir = extract(fmu_path)
    other = FMU2Slave(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="other",
    )
    other.instantiate()
    restored = other.deSerializeFMUstate(blob)
    other.setFMUstate(restored)
    assert steps(other, 20, 30) == first
    other.freeFMUstate(restored)
    other.freeInstance()
    slave.freeFMUstate(state)

    with pytest.raises(FMICallException):
        slave.deSerializeFMUstate(b"not a state at all")


def test_huge_force_discards_recoverably_and_rollback_continues(slave, vrs, huge_force):
    """A failing step is a recoverable fmi2Discard: fmi2Terminated = false, the FMU keeps its
    state at lastSuccessfulTime, and fmi2SetFMUstate to a saved state continues."""
    h = 0.01
    for k in range(10):
        slave.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
    kept = slave.getReal([vrs[n] for n in POSITIONS])
    saved = slave.getFMUstate()
    slave.setReal([vrs["tip.force.x"]], [huge_force])
    with pytest.raises(FMICallException) as failure:
        slave.doStep(currentCommunicationPoint=10 * h, communicationStepSize=h)
    assert failure.value.status == fmi2Discard
    assert not slave.getBooleanStatus(fmi2Terminated)
    assert slave.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(10 * h, abs=1e-12)
    assert slave.getReal([vrs[n] for n in POSITIONS]) == kept
    slave.setFMUstate(saved)
    slave.doStep(currentCommunicationPoint=10 * h, communicationStepSize=h)
    assert slave.getReal([vrs[n] for n in POSITIONS]) != kept
    slave.freeFMUstate(saved)
    slave.terminate()


def test_simulate_fmu_does_not_pass_a_recoverable_discard(fmu_path, huge_force):
    """fmpy's simulate_fmu stops only on fmi2Discard with fmi2Terminated = true; on a recoverable
    one it neither restores a state nor stops, and calls fmi2DoStep again in stepFailed, which the
    FMU refuses (fmi2Error, as FMI 2.0 requires): the run ends with an exception, not with
    silently wrong results."""
    inp = np.array(
        [(0.0, 0.0), (0.5, 0.0), (0.5, huge_force), (1.0, huge_force)],
        dtype=[("time", "f8"), ("tip.force.x", "f8")],
    )
    with pytest.raises(FMICallException) as failure:
        simulate_fmu(fmu_path, stop_time=1.0, output_interval=0.01, input=inp, output=POSITIONS)
    assert failure.value.status == fmi2Error


def test_station_at_the_root_through_fmpy_is_minus_the_reaction(fmu_path, md):
    """A station named `root_weld` (the shipped sprayer booms' station at the root; skipped for
    FMUs without it) read through fmpy: its force and moment equal minus `root.force.*` and
    `root.moment.*` at every output (the clamped root's section frame is the world's; docs/
    stations.md), and its stress is finite and positive once gravity loads the arm."""
    names = {v.name for v in md.modelVariables}
    if "station.root_weld.stress" not in names:
        pytest.skip("no root_weld station in this FMU")
    pairs = [
        (f"station.root_weld.{q}.{a}", f"root.{q}.{a}")
        for q in ("force", "moment")
        for a in "xyz"
        if f"station.root_weld.{q}.{a}" in names
    ]
    outputs = [n for p in pairs for n in p] + ["station.root_weld.stress"]
    res = simulate_fmu(fmu_path, stop_time=0.1, output_interval=0.01, output=outputs)
    scale = max(np.max(np.abs(res[r])) for _, r in pairs)
    assert scale > 1.0
    for s, r in pairs:
        assert np.max(np.abs(res[s] + res[r])) <= 1e-9 * scale, (s, r)
    stress = res["station.root_weld.stress"]
    assert np.all(np.isfinite(stress)) and stress[-1] > 1e6
