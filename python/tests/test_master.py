"""The master's algorithms on two linear oscillators coupled through the car–beam interface
(`oscillators.py`), against closed forms: the implicit scheme equals the monolithic
generalized-α solution to its iteration tolerance; the naive loop grows at the spectral radius
of its one-step map."""

import pathlib

import numpy as np
import pytest
from hybeam.cosim.master import Settings, run
from hybeam.cosim.system import (
    Connection,
    Energy,
    Scheme,
    System,
    SystemFileError,
    load,
)
from oscillators import (
    Carried,
    Carrier,
    consistent_start,
    monolithic,
    naive_matrix,
)

# a base as heavy as the carrier (m0 = m1): the naive loop's held reaction diverges
P = dict(m0=1.0, m1=1.0, m2=2.0, k1=400.0, k2=4.0e4)


def system(ledger=False):
    fw = [Connection("carrier", n, "carried", n) for n in ("position", "velocity", "acceleration")]
    back = [Connection("carried", "force", "carrier", "force")]
    return System(
        pathlib.Path("oscillators"),
        {},
        {"all": fw + back},
        {
            "naive": Scheme("naive", "naive", ["all"]),
            "implicit": Scheme("implicit", "implicit", ["all"]),
        },
        ["carrier", "carried"],
        [],
        Energy(stored=[("carrier", "energy"), ("carried", "energy")]) if ledger else Energy(),
        [("carrier", "position"), ("carried", "position"), ("carried", "force")],
        [],
    )


def subsystems(rho, x1=0.01, x2=0.0):
    a1, a2, f = consistent_start(P["m0"], P["m1"], P["m2"], P["k1"], P["k2"], x1, x2)
    return {
        "carrier": Carrier(P["m1"], P["k1"], rho, x1, 0.0, a1, f),
        "carried": Carried(P["m0"], P["m2"], P["k2"], rho, (x1, 0.0, a1), x2, 0.0, a2),
    }


@pytest.mark.parametrize("rho", [1.0, 0.8, 0.5])
def test_implicit_equals_the_monolithic_generalized_alpha_solution(rho):
    h, n = 2e-3, 500
    ref = monolithic(P["m0"], P["m1"], P["m2"], P["k1"], P["k2"], rho, h, n, 0.01, 0.0)
    res = run(
        system(),
        "implicit",
        subsystems(rho),
        h,
        n * h,
        Settings(rtol=1e-12, atol=1e-14, max_iterations=30),
    )
    assert res.stable, res.message
    got = res.table()[:, 1:4]
    err = np.max(np.abs(got - ref), axis=0) / np.max(np.abs(ref), axis=0)
    print(
        f"rho_inf {rho}: relative difference to the monolithic solution {err}, "
        f"{res.iterations:.2f} iterations per step"
    )
    assert np.all(err < 1e-9), err
    # the feedthrough Jacobian's Newton start and IQN-ILS converge in a few iterations
    assert res.iterations < 6


def test_naive_loop_grows_at_the_spectral_radius_of_its_step_map():
    rho, h, n = 0.9, 2e-3, 400
    G = naive_matrix(P["m0"], P["m1"], P["m2"], P["k1"], P["k2"], rho, h)
    radius = np.max(np.abs(np.linalg.eigvals(G)))
    assert radius > 1.05  # the heavy base makes the held reaction unstable
    res = run(system(), "naive", subsystems(rho), h, n * h)
    x = np.abs(res.column("carrier.position"))
    # the envelope's growth per step over the last half (past the transients)
    a, b = n // 2, n
    observed = (np.max(x[b - 20 : b + 1]) / np.max(x[a - 20 : a + 1])) ** (1.0 / (b - a))
    print(f"spectral radius {radius:.6f}, observed growth per step {observed:.6f}")
    assert abs(observed - radius) < 2e-3 * radius
    # the implicit scheme on the same case stays bounded (energy of a conservative pair)
    imp = run(system(), "implicit", subsystems(rho), h, n * h)
    assert np.max(np.abs(imp.column("carrier.position"))) < 0.02


def test_the_energy_ledger_closes_for_the_energy_conserving_member_of_the_family():
    """ρ∞ = 1 (the trapezoidal rule) conserves the energy of the undamped linear pair: the
    implicit scheme's coupled ledger stays at the iteration tolerance; the naive loop's grows."""
    h, n = 2e-3, 500
    res = run(system(True), "implicit", subsystems(1.0), h, n * h, Settings(rtol=1e-12, atol=1e-14))
    print(f"implicit: energy residual {res.energy_residual:.3e} J of {res.energy_scale:.3e} J")
    assert res.stable and res.energy_residual < 1e-9 * res.energy_scale
    naive = run(system(True), "naive", subsystems(1.0), h, 50 * h)
    print(f"naive: energy residual {naive.energy_residual:.3e} J of {naive.energy_scale:.3e} J")
    assert not naive.stable and "over 1 % of its scale" in naive.message


def test_a_non_converging_step_is_refused_with_a_message():
    res = run(
        system(),
        "implicit",
        subsystems(0.9),
        2e-3,
        0.1,
        Settings(max_iterations=1, newton_start=False),
    )
    assert not res.stable
    assert "did not converge in 1 iterations" in res.message and "t = 0 s" in res.message


def test_bad_system_files_name_the_field_the_value_and_the_fix(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(
        '[fmus.a]\npath = "a.fmu"\n[fmus.b]\npath = "b.fmu"\n[connections]\ng = [["a.x", "c.y"]]\n'
    )
    with pytest.raises(SystemFileError, match=r"connections.g\[0\] = .*'c' is not an FMU"):
        load(f)
    f.write_text('[fmus.a]\npath = "a.fmu"\n[schemes]\nfast = { algorithm = "magic" }\n')
    with pytest.raises(SystemFileError, match="schemes.fast.algorithm = 'magic': choose one"):
        load(f)
    f.write_text('[fmus.a]\npath = "a.fmu"\n[system]\nstep = -1\n')
    with pytest.raises(SystemFileError, match="system.step = -1: give a positive number"):
        load(f)
