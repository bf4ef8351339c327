"""The car + boom co-simulation in libcosim (libcosimpy): the same FMUs and connections as
cosim.py, described by an OSP system structure (examples/vehicle/OspSystemStructure.xml: one
VariableGroupConnection per OSP-IS port group of the two FMUs, the *_OspModelDescription.xml
files their packagers write beside them;
libcosim's fixed-step algorithm: a Jacobi exchange at the base step), compared with the
fmpy master's naive Jacobi loop at the same step.

Usage: python cosim_libcosim.py CAR.fmu BOOM.fmu [--t-end 1.0] [--heavy]
(the base step is the structure file's BaseStepSize, 1 ms). --heavy: the 20x denser boom at
1.5 ms built through libcosim's API (run_libcosim_connected), the naive exchange against
interface mass (the beam's root.force_elastic and rigid inertia to the car).
"""

import argparse
import pathlib
import shutil
import sys
import tempfile

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from cosim import ELASTIC, INERTIA, MOUNT, REACTION, run  # noqa: E402

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


def run_libcosim_connected(car, boom, t_end, h, scheme="jacobi", density_factor=1.0):
    """The same pair built through libcosim's API instead of a structure file, at base step
    `h`, variable by variable: the car's mount.* outputs to the beam's root.* inputs, and back
    either the reaction (`jacobi`, the naive exchange) or, for interface mass (`interface`),
    the beam's rigid inertia (root.mass, root.center_of_mass.*, root.inertia.zz) to the car's
    payload inputs and the reaction beyond it (root.force_elastic, root.moment_elastic) to
    the car's beam.root.* inputs; the boom's densities scaled by `density_factor` (initial
    values). Returns (ok, times, {name: samples}): ok is false when libcosim stops early (a
    step refused)."""
    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    ex = CosimExecution.from_step_size(step_size=int(round(h * 1e9)))
    ci = ex.add_local_slave(CosimLocalSlave(fmu_path=str(car), instance_name="car"))
    bi = ex.add_local_slave(CosimLocalSlave(fmu_path=str(boom), instance_name="boom"))
    vr = {i: {v.name.decode(): v.reference for v in ex.slave_variables(i)} for i in (ci, bi)}
    for n in MOUNT:
        ex.connect_real_variables(ci, vr[ci]["mount." + n], bi, vr[bi]["root." + n])
    given = ELASTIC if scheme == "interface" else REACTION
    for src, dst in zip(given, REACTION):
        ex.connect_real_variables(bi, vr[bi][src], ci, vr[ci]["beam." + dst])
    if scheme == "interface":
        for n in INERTIA:
            ex.connect_real_variables(bi, vr[bi][n], ci, vr[ci]["beam." + n])
    if density_factor != 1.0:
        for v in read_model_description(boom).modelVariables:
            if v.name.endswith(".density"):
                ex.real_initial_value(bi, vr[bi][v.name], density_factor * float(v.start))
    return simulate_observed(ex, h, t_end)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("car")
    p.add_argument("boom")
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument("--heavy", action="store_true",
                   help="also the 20x boom at 1.5 ms, naive vs interface mass, through the API")
    a = p.parse_args()
    t, lc = run_libcosim(a.car, a.boom, a.t_end)
    print(f"libcosim: {len(t)} samples to t = {t[-1]:.3f} s")
    rows, _, ok = run(a.car, a.boom, 1e-3, a.t_end, "jacobi")
    cols = {"body.heave": 1, "body.pitch": 2, "root.force.y": 7}
    for name, c in cols.items():
        ref = np.interp(t, rows[:, 0], rows[:, c])
        print(f"{name}: libcosim vs fmpy Jacobi max |Δ| {np.max(np.abs(lc[name] - ref)):.3e} "
              f"(range {np.ptp(rows[:, c]):.3e})")
    if a.heavy:
        for scheme in ("jacobi", "interface"):
            ok, t, lc = run_libcosim_connected(a.car, a.boom, 1.5, 1.5e-3, scheme, 20.0)
            line = f"20x boom, 1.5 ms, {scheme}: {'ran' if ok else 'stopped'} to {t[-1]:.4f} s"
            if ok:
                rows, _, _ = run(a.car, a.boom, 1.5e-3, 1.5, scheme, 20.0)
                ref = np.interp(t, rows[:, 0], rows[:, 2])
                line += (f", body pitch vs fmpy {np.max(np.abs(lc['body.pitch'] - ref)):.3e} "
                         f"(range {np.ptp(rows[:, 2]):.3e})")
            else:
                line += f", |root.force.y| up to {np.max(np.abs(lc['root.force.y'])):.3e} N"
            print(line)


if __name__ == "__main__":
    main()
