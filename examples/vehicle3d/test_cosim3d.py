"""The spatial vehicle example through hybeam-cosim (python/hybeam/cosim), each check against
an independent reference: the coupled energy balance (a conservation law: the boom is
undamped), the planar system (examples/vehicle/system.toml) in the rolling-symmetric case, and
the stability of the heavy boom (the implicit scheme against the naive exchange)."""

import pathlib
import subprocess

import numpy as np
import pytest
from hybeam.cosim.run import simulate
from hybeam.cosim.system import load

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
SYSTEM = HERE / "system.toml"
PLANAR = ROOT / "examples" / "vehicle" / "system.toml"
# the packager and the car's library (examples/vehicle3d/run.sh builds them)
PACKAGER = ROOT / "target" / "release" / "car3d-fmu"
LIBRARY = ROOT / "target" / "release" / "libhybeam_vehicle3d.so"


def cosim(system_path, car, boom, scheme, h, t_end, sets=(), record=None):
    """hybeam-cosim's run of a system file with these FMUs (a `Result`); `record` replaces
    the recorded columns ("fmu.variable")."""
    system = load(system_path, {"car": car, "boom": boom})
    if record is not None:
        system.record = [tuple(c.split(".", 1)) for c in record]
    return simulate(system, scheme, h, t_end, sets)


def test_one_sided_bump_rolls_the_car_and_swings_the_boom_sideways(fmus):
    """The shipped car (bump under the left wheels) with the boom, implicit coupling at 1 ms
    over 1.5 s: every step converges, the coupled energy balance ΔE_car + ΔE_beam − W_road −
    W_drive + D closes within 1e-3 of its scale (the beam is undamped: the residual is the
    coupling and integration error only), and the motion leaves the x-z plane: the car rolls
    and the boom tip moves sideways (the pitch-plane car and boom cannot)."""
    car, boom = fmus
    res = cosim(SYSTEM, car, boom, "implicit", 1e-3, 1.5)
    roll = res.column("car.body.roll")
    tip_y = res.column("boom.tip.position.y")
    print(
        f"implicit 1 ms: residual {res.energy_residual:.3e} J of {res.energy_scale:.3e} J, "
        f"{res.iterations:.2f} iterations per step; max |roll| {np.max(np.abs(roll)):.3e} rad, "
        f"max |tip y| {np.max(np.abs(tip_y)):.3e} m, max |root force y| "
        f"{np.max(np.abs(res.column('boom.root.force.y'))):.3e} N"
    )
    assert res.stable and res.steps == 1500, res.message
    assert res.energy_residual < 1e-3 * res.energy_scale
    # the car starts level (static, symmetric load): roll and lateral tip position are zero
    assert abs(roll[0]) < 1e-12 and abs(tip_y[0]) < 1e-9
    # measured: max |roll| 3.7e-3 rad, max |tip y| 7.3e-3 m (rounding level: ~1e-12)
    assert np.max(np.abs(roll)) > 1e-3
    assert np.max(np.abs(tip_y)) > 2e-3


def _symmetric_car(tmp_path):
    """The spatial car with the bump across the road (sides = "both", no lateral offset) and
    each axle's two wheels together the pitch-plane car's wheel (README: vehicle.toml's wheel
    stands for an axle, so 20 kg on 100 kN/m each here = 40 kg on 200 kN/m per axle there),
    packaged with car3d-fmu."""
    text = (HERE / "vehicle3d.toml").read_text()
    for old, new in [
        ('sides = "left"', 'sides = "both"'),
        ("mass = 40.0 ", "mass = 20.0 "),
        ("tire_stiffness = 200000.0", "tire_stiffness = 100000.0"),
        ('name = "vehicle3d"', 'name = "vehicle3d_symmetric"'),
    ]:
        assert old in text, old
        text = text.replace(old, new)
    assert "position = [0.3, 0.0, 0.9]" in text  # no lateral offset
    resource = tmp_path / "vehicle3d.toml"
    resource.write_text(text)
    out = tmp_path / "car3d_symmetric.fmu"
    subprocess.run([str(PACKAGER), str(LIBRARY), str(resource), str(out)], check=True)
    return out


def test_rolling_symmetric_case_equals_the_planar_system(fmus, planar_fmus, tmp_path):
    """Bump across the road, no lateral offset, the axles' masses and tires those of the pitch-plane
    car: the spatial pair (car3d + boom_3d) and the planar pair (examples/vehicle: car + boom)
    at 1 ms, implicit, over the bump (0.8 s), agree: heave, pitch (planar = −3D), the boom tip's
    x and height (3D z, planar y, as changes from t = 0: the two booms' mounts sit at different
    static heights), the root force (3D z = planar y, x = x) and moment (3D y = −planar z). The
    cars agree to rounding (tests/car3d.rs) and the spatial boom in its plane is the planar
    boom's discretization (both modal bodies geometrically nonlinear: with the planar one
    nonlinear and the spatial one linear, as before, they differed by 7.4e-9 of the pitch range,
    more than the bound); what separates the runs is the coupling
    tolerance: each accepts a step's reaction (the iterated unknowns) within rtol = 1e-5 of the
    largest reaction component (~280 N m: ~3e-3 N, N m), so the reactions may differ by twice
    that (measured: force x 5.7e-3 N, force z 3.0e-4 N, moment y 5.1e-5 N m; bound 4 rtol
    max|reaction|), and the motions by its effect, tiny on the 1.2 t car (measured: heave,
    pitch, tip x and height ≤ 1.3e-8 of their ranges; bound 1e-6). Roll and every out-of-plane
    value (tip y, root force y, root moments x and z) stay at rounding level (measured exactly
    0; bound 1e-9 m, rad, N, N m: the symmetric problem stays symmetric)."""
    sym = _symmetric_car(tmp_path)
    t_end = 0.8
    spatial = cosim(
        SYSTEM,
        sym,
        fmus[1],
        "implicit",
        1e-3,
        t_end,
        record=[
            "car.body.heave",
            "car.body.pitch",
            "car.body.roll",
            "boom.tip.position.x",
            "boom.tip.position.y",
            "boom.tip.position.z",
            "boom.root.force.x",
            "boom.root.force.y",
            "boom.root.force.z",
            "boom.root.moment.x",
            "boom.root.moment.y",
            "boom.root.moment.z",
        ],
    )
    planar = cosim(
        PLANAR,
        *planar_fmus,
        "implicit",
        1e-3,
        t_end,
        record=[
            "car.body.heave",
            "car.body.pitch",
            "boom.tip.position.x",
            "boom.tip.position.y",
            "boom.root.force.x",
            "boom.root.force.y",
            "boom.root.moment.z",
        ],
    )
    assert spatial.stable and planar.stable, (spatial.message, planar.message)
    assert len(spatial.rows) == len(planar.rows) == 801

    def change(x):
        return x - x[0]

    reactions = ["boom.root.force.x", "boom.root.force.z", "boom.root.moment.y"]
    # the coupling tolerance on the reaction (the implicit scheme's unknowns), both runs
    coupling = 4 * 1e-5 * max(np.max(np.abs(spatial.column(c))) for c in reactions)
    pairs = [
        ("car.body.heave", 1.0, "car.body.heave", False),
        ("car.body.pitch", -1.0, "car.body.pitch", False),
        ("boom.tip.position.x", 1.0, "boom.tip.position.x", True),
        ("boom.tip.position.z", 1.0, "boom.tip.position.y", True),
        ("boom.root.force.x", 1.0, "boom.root.force.x", False),
        ("boom.root.force.z", 1.0, "boom.root.force.y", False),
        ("boom.root.moment.y", -1.0, "boom.root.moment.z", False),
    ]
    for s, sign, p, relative in pairs:
        a, b = spatial.column(s), sign * planar.column(p)
        if relative:
            a, b = change(a), change(b)
        d = np.max(np.abs(a - b))
        bound = coupling if s in reactions else 1e-6 * np.ptp(b)
        print(
            f"{s} vs {sign:+.0f} x planar {p}: max |diff| {d:.3e} (bound {bound:.1e}) "
            f"of range {np.ptp(b):.3e}"
        )
        assert np.ptp(b) > 0.0, s
        assert d < bound, (s, d, bound)
    for s in [
        "car.body.roll",
        "boom.tip.position.y",
        "boom.root.force.y",
        "boom.root.moment.x",
        "boom.root.moment.z",
    ]:
        m = np.max(np.abs(spatial.column(s)))
        print(f"{s}: max |value| {m:.3e}")
        assert m < 1e-9, (s, m)


def test_heavy_boom_needs_the_implicit_scheme(fmus):
    """The boom 100 times heavier (same shape and frequencies: --set boom.mass_factor=100,
    1.04 t on the 1.2 t car) at 5 ms over the one-sided bump (1.5 s): the implicit scheme
    converges at every step and its coupled energy residual stays within 1 % of its scale;
    the naive exchange diverges (a refused step or an energy residual beyond the ledger's)."""
    car, boom = fmus
    sets = ["boom.mass_factor=100"]
    res = cosim(SYSTEM, car, boom, "implicit", 5e-3, 1.5, sets)
    print(
        f"x100, implicit 5 ms: residual {res.energy_residual:.3e} J of {res.energy_scale:.3e} J, "
        f"{res.iterations:.2f} iterations per step"
    )
    assert res.stable and res.steps == 300, res.message
    assert res.energy_residual < 1e-2 * res.energy_scale
    naive = cosim(SYSTEM, car, boom, "naive", 5e-3, 1.5, sets)
    print(f"x100, naive 5 ms: {naive.message} after {naive.steps} steps")
    assert not naive.stable


def test_the_partner_model_keeps_the_naive_exchange_of_the_heavy_boom_bounded(fmus):
    """The x100 spatial boom at 5 ms, 2 s over the one-sided bump, naive exchange with the beam
    FMU's partner model (the car's 6x6 mobility at the mount, docs/coupling.md): every step
    taken and the energy residual within 20 h/s of the scale (measured 6.0 %: first order in h,
    above the map's 1 %), where the naive exchange alone diverges
    (test_heavy_boom_needs_the_implicit_scheme)."""
    car, boom = fmus
    res = cosim(SYSTEM, car, boom, "partner", 5e-3, 2.0, ["boom.mass_factor=100"])
    print(f"x100, partner 5 ms: residual {res.energy_residual:.3e} J of {res.energy_scale:.3e} J")
    assert res.steps == 400, res.message
    assert res.energy_residual < 0.1 * res.energy_scale


@pytest.mark.parametrize("scheme", ["interface", "implicit-interface"])
def test_interface_mass_schemes_start_in_the_same_equilibrium(fmus, scheme):
    """The interface-mass schemes (the beam's rigid inertia to the car as a payload plus the
    reaction beyond it) give the car the same total load as the reaction alone: before the
    bump (0.1 s) the pair rests in the implicit scheme's static equilibrium (body heave and
    pitch, the boom's root force and moment) to 1e-6 of their values."""
    car, boom = fmus
    ref = cosim(SYSTEM, car, boom, "implicit", 1e-3, 0.1)
    res = cosim(SYSTEM, car, boom, scheme, 1e-3, 0.1)
    # at rest the ledger's scale is itself rounding (~4e-8 J), so `stable` (residual < 1 % of
    # the scale) means nothing here: every step is taken and the residual stays at rounding
    assert res.steps == 100 and res.energy_residual < 1e-6, res.message
    for c in ("car.body.heave", "car.body.pitch", "boom.root.force.z", "boom.root.moment.y"):
        d = np.max(np.abs(res.column(c) - ref.column(c)))
        print(f"{scheme}: {c} vs implicit {d:.3e} of {np.max(np.abs(ref.column(c))):.3e}")
        assert d < 1e-6 * np.max(np.abs(ref.column(c))), (c, d)


def test_the_shipped_ssd_is_valid_ssp_and_the_system_files_twin():
    """examples/vehicle3d/system.ssd validates against the SSP 1.0 schema (fmpy's XSDs) and is
    what `hybeam-ssp system.toml --out system.ssd` writes (the implicit scheme's connections)."""
    import os

    from hybeam.cosim import ssp

    ssd = SYSTEM.with_suffix(".ssd")
    ssp.validate(ssd)
    toml = load(SYSTEM)
    sources = {n: os.path.relpath(f.path, HERE) for n, f in toml.fmus.items()}
    assert ssd.read_text() == ssp.ssd_text(toml, "implicit", sources, "vehicle3d")


def test_a_run_from_the_ssp_equals_the_run_from_the_toml_bit_for_bit(fmus, tmp_path):
    """system.toml, the shipped system.ssd (the FMUs by --fmu) and an .ssp archive packed with
    the FMUs (hybeam-ssp): 30 ms at 1 ms of the implicit scheme, every recorded value equal
    bit for bit."""
    from hybeam.cosim import ssp

    car, boom = fmus
    paths = {"car": car, "boom": boom}
    toml = load(SYSTEM, paths)
    archive = ssp.export(toml, "implicit", tmp_path / "vehicle3d.ssp")
    ref = simulate(toml, "implicit", 1e-3, 0.03)
    for system in (load(SYSTEM.with_suffix(".ssd"), paths), load(archive)):
        res = simulate(system, "implicit", 1e-3, 0.03)
        assert res.columns == ref.columns
        assert np.array_equal(res.table(), ref.table(), equal_nan=True), system.path
