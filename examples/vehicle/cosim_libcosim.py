"""The car + boom co-simulation in libcosim (libcosimpy), a host that only exchanges values:
the OSP system structure (examples/vehicle/OspSystemStructure.xml: one VariableGroupConnection
per OSP-IS port group of the two FMUs, the *_OspModelDescription.xml files their packagers
write beside them), or the connections of a scheme of examples/vehicle/system.toml built
through libcosim's API (run_libcosim_connected: connections only, no master arithmetic);
libcosim's fixed-step algorithm is a Jacobi exchange at the base step, the same as
hybeam-cosim's naive scheme, which it is compared with.

Usage: python cosim_libcosim.py CAR.fmu BOOM.fmu [--t-end 1.0] [--heavy]
(the base step is the structure file's BaseStepSize, 1 ms). --heavy: the 20x boom at 1.5 ms
through the API, the naive exchange against interface mass (the beam's root.force_elastic and
rigid inertia to the car).
"""

import argparse
import pathlib
import shutil
import tempfile

import numpy as np
from hybeam.cosim.run import simulate
from hybeam.cosim.system import load

HERE = pathlib.Path(__file__).resolve().parent
SYSTEM = HERE / "system.toml"

PROBES = {"car": ["body.heave", "body.pitch"], "boom": ["tip.position.y", "root.force.y"]}


def simulate_observed(ex, h, t_end):
    """Runs the execution `ex` (slaves "car" and "boom", base step `h`) to `t_end`, recording
    PROBES; returns (ok, times, {name: samples}): ok is false when libcosim stops early (a step
    refused) or a sample is not finite."""
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimObserver import CosimObserver

    obs = CosimObserver.create_time_series()
    ex.add_observer(obs)
    refs = {}
    for name, probes in PROBES.items():
        i = ex.slave_index_from_instance_name(name)
        vr = {v.name.decode(): v.reference for v in ex.slave_variables(i)}
        for p in probes:
            refs[p] = (i, vr[p])
            obs.start_time_series(i, value_reference=vr[p], variable_type=CosimVariableType.REAL)
    ok = bool(ex.simulate_until(target_time=int(round(t_end * 1e9))))
    n = int(round(t_end / h)) + 1
    out, times = {}, None
    for p, (i, r) in refs.items():
        t, _, values = obs.time_series_real_samples(i, r, from_step=0, sample_count=n)
        out[p] = np.array(values)
        times = np.array(t) * 1e-9
    ok = ok and times[-1] > t_end - 1.5 * h and all(np.all(np.isfinite(v)) for v in out.values())
    return ok, times, out


def run_libcosim(car, boom, t_end):
    """Runs the OSP system structure with the two FMUs; returns (times, {name: samples})."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level

    log_output_level(CosimLogLevel.WARNING)
    with tempfile.TemporaryDirectory() as d:
        shutil.copy(HERE / "OspSystemStructure.xml", d)
        shutil.copy(car, pathlib.Path(d) / "car.fmu")
        shutil.copy(boom, pathlib.Path(d) / "boom.fmu")
        # the port groups the connections name, written beside each FMU by its packager
        for fmu in (car, boom):
            for osp in pathlib.Path(fmu).parent.glob("*_OspModelDescription.xml"):
                shutil.copy(osp, d)
        ex = CosimExecution.from_osp_config_file(osp_path=d)
        ok, times, out = simulate_observed(ex, 1e-3, t_end)
        assert ok, "libcosim failed"
    return times, out


def run_libcosim_connected(car, boom, t_end, h, scheme="naive", factor=1.0, knob="mass_factor"):
    """The pair built through libcosim's API at base step `h` with the connections of a naive
    scheme of system.toml (`naive`: the mount motion and the reaction; `interface`: the mount
    motion, the beam's rigid inertia and the reaction beyond it), the boom's `knob` (a knob of
    system.toml) at `factor` applied to the initial values. Returns (ok, times, {name:
    samples}): ok is false when libcosim stops early (a step refused)."""
    import fnmatch

    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimSlave import CosimLocalSlave

    system = load(SYSTEM)
    log_output_level(CosimLogLevel.ERROR)
    ex = CosimExecution.from_step_size(step_size=int(round(h * 1e9)))
    index = {
        n: ex.add_local_slave(CosimLocalSlave(fmu_path=str(p), instance_name=n))
        for n, p in (("car", car), ("boom", boom))
    }
    vr = {
        n: {v.name.decode(): v.reference for v in ex.slave_variables(i)} for n, i in index.items()
    }
    for c in system.connections(scheme):
        ex.connect_real_variables(
            index[c.src], vr[c.src][c.src_var], index[c.dst], vr[c.dst][c.dst_var]
        )
    if factor != 1.0:
        for v in read_model_description(boom).modelVariables:
            if any(fnmatch.fnmatchcase(v.name, p) for p in system.fmus["boom"].knobs[knob]):
                ex.real_initial_value(index["boom"], vr["boom"][v.name], factor * float(v.start))
    return simulate_observed(ex, h, t_end)


# the scalar power bonds of the mount: (car output, car input, boom output, boom input)
BONDS = [
    ("mount.velocity.x", "beam.root.force.x", "root.force.x", "root.velocity.x"),
    ("mount.velocity.y", "beam.root.force.y", "root.force.y", "root.velocity.y"),
    ("mount.angular_velocity", "beam.root.moment.z", "root.moment.z", "root.angular_velocity"),
]


def run_ecco(car, boom, t_end, h, mass_factor=1.0):
    """libcosim's ECCO algorithm (energy-conservation-based step control, Sadjina & Pedersen,
    Eng. with Computers 36:1579-1587, 2020) on the naive connections of system.toml with a
    power bond per mount axis (force x velocity), starting at and limited to the communication
    step `h` (down to h/100), the libcosimpy 0.0.6 defaults otherwise. Returns a summary like
    hybeam-cosim's: stable, energy_residual, energy_scale (the same ledger as system.toml's,
    read after every step), steps, wall_s, message."""
    import fnmatch
    import time

    from fmpy import read_model_description
    from libcosimpy.CosimAlgorithm import CosimAlgorithm, EccoParams
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    system = load(SYSTEM)
    log_output_level(CosimLogLevel.ERROR)
    algo = CosimAlgorithm.create_ecco_algorithm(
        EccoParams(step_size=h, min_step_size=h / 100, max_step_size=h)
    )
    ex = CosimExecution.from_algorithm(algo)
    index = {
        n: ex.add_local_slave(CosimLocalSlave(fmu_path=str(p), instance_name=n))
        for n, p in (("car", car), ("boom", boom))
    }
    vr = {
        n: {v.name.decode(): v.reference for v in ex.slave_variables(i)} for n, i in index.items()
    }
    for c in system.connections("naive"):
        ex.connect_real_variables(
            index[c.src], vr[c.src][c.src_var], index[c.dst], vr[c.dst][c.dst_var]
        )
    for co, ci, bo, bi in BONDS:
        algo.add_power_bond(
            index["car"],
            vr["car"][co],
            vr["car"][ci],
            index["boom"],
            vr["boom"][bo],
            vr["boom"][bi],
        )
    if mass_factor != 1.0:
        for v in read_model_description(boom).modelVariables:
            if any(
                fnmatch.fnmatchcase(v.name, p) for p in system.fmus["boom"].knobs["mass_factor"]
            ):
                ex.real_initial_value(
                    index["boom"], vr["boom"][v.name], mass_factor * float(v.start)
                )
    obs = CosimObserver.create_last_value()
    ex.add_observer(obs)
    e = system.energy
    terms = {k: [(f, v) for f, v in getattr(e, k)] for k in ("stored", "supplied", "dissipated")}

    def ledger():
        val = {}
        for f, v in [x for xs in terms.values() for x in xs]:
            val[(f, v)] = obs.last_real_values(index[f], [vr[f][v]])[0]
        return (
            [val[x] for x in terms["stored"]],
            sum(val[x] for x in terms["supplied"]),
            sum(val[x] for x in terms["dissipated"]),
        )

    t0 = time.perf_counter()
    ex.step(1)
    e0 = ledger()[0]
    worst = scale = 0.0
    steps, message = 1, ""
    while ex.status().current_time < int(round(t_end * 1e9)) - 1000:
        if not ex.step(1):
            message = f"libcosim stopped at t = {ex.status().current_time * 1e-9:.6g} s"
            break
        steps += 1
        stored, supplied, dissipated = ledger()
        d = [a - b for a, b in zip(stored, e0, strict=True)]
        res = sum(d) - supplied + dissipated
        scale = max(scale, sum(abs(x) for x in d) + abs(supplied) + abs(dissipated))
        worst = max(worst, abs(res)) if np.isfinite(res) else float("inf")
        if worst > e.divergence:
            t = ex.status().current_time * 1e-9
            message = f"diverged: energy residual {res:.3e} J at t = {t:.6g} s"
            break
    stable = not message and worst < 1e-2 * scale
    return {
        "stable": stable,
        "energy_residual": worst,
        "energy_scale": scale,
        "steps": steps,
        "wall_s": time.perf_counter() - t0,
        "message": message,
    }


def master(car, boom, scheme, h, t_end, factor=1.0, knob="mass_factor"):
    """hybeam-cosim's run of system.toml with these FMUs (a `Result`), the boom's `knob` at
    `factor`."""
    system = load(SYSTEM, {"car": car, "boom": boom})
    return simulate(system, scheme, h, t_end, [f"boom.{knob}={factor}"])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("car")
    p.add_argument("boom")
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument(
        "--heavy",
        action="store_true",
        help="also the 20x boom at 1.5 ms, naive vs interface mass, through the API",
    )
    p.add_argument(
        "--ecco-row",
        metavar="OUT.md",
        help="instead: libcosim's ECCO on the map's cells (steps 1, 5, 20 ms x mass factors "
        "1, 10, 100, 2 s) written as a markdown table",
    )
    a = p.parse_args()
    if a.ecco_row:
        steps, factors = (1e-3, 5e-3, 2e-2), (1, 10, 100)
        lines = [
            "libcosim ECCO (step from h down to h/100, power bonds on the mount's three axes): "
            "energy residual / scale (✗: not stable), steps taken, wall time",
            "",
            "| mass_factor \\ h [ms] | " + " | ".join(f"{1e3 * h:g}" for h in steps) + " |",
            "|---" * (len(steps) + 1) + "|",
        ]
        for f in factors:
            cells = []
            for h in steps:
                r = run_ecco(a.car, a.boom, 2.0, h, f)
                frac = r["energy_residual"] / max(r["energy_scale"], 1e-300)
                cells.append(
                    f"{'' if r['stable'] else '✗ '}{frac:.1e} ({r['steps']} steps, "
                    f"{r['wall_s']:.0f} s)"
                )
                print(f, h, r, flush=True)
            lines.append(f"| {f:g} | " + " | ".join(cells) + " |")
        pathlib.Path(a.ecco_row).write_text("\n".join(lines) + "\n")
        print("\n".join(lines))
        return
    t, lc = run_libcosim(a.car, a.boom, a.t_end)
    print(f"libcosim: {len(t)} samples to t = {t[-1]:.3f} s")
    res = master(a.car, a.boom, "naive", 1e-3, a.t_end)
    for name in ("car.body.heave", "car.body.pitch", "boom.root.force.y"):
        col = res.column(name)
        ref = np.interp(t, res.column("time"), col)
        d = np.max(np.abs(lc[name.split(".", 1)[1]] - ref))
        print(f"{name}: libcosim vs hybeam-cosim naive max |Δ| {d:.3e} (range {np.ptp(col):.3e})")
    if a.heavy:
        for scheme in ("naive", "interface"):
            ok, t, lc = run_libcosim_connected(
                a.car, a.boom, 1.5, 1.5e-3, scheme, 20.0, "density_factor"
            )
            line = f"20x boom, 1.5 ms, {scheme}: {'ran' if ok else 'stopped'} to {t[-1]:.4f} s"
            if ok:
                res = master(a.car, a.boom, scheme, 1.5e-3, 1.5, 20.0, "density_factor")
                pitch = res.column("car.body.pitch")
                ref = np.interp(t, res.column("time"), pitch)
                line += (
                    f", body pitch vs hybeam-cosim {np.max(np.abs(lc['body.pitch'] - ref)):.3e} "
                    f"(range {np.ptp(pitch):.3e})"
                )
            else:
                line += f", |root.force.y| up to {np.max(np.abs(lc['root.force.y'])):.3e} N"
            print(line)


if __name__ == "__main__":
    main()
