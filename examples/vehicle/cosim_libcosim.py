"""The car + boom co-simulation in libcosim (libcosimpy): the same FMUs and connections as
cosim.py, described by an OSP system structure (examples/vehicle/OspSystemStructure.xml: one
VariableGroupConnection per OSP-IS port group of the two FMUs, the *_OspModelDescription.xml
files their packagers write beside them;
libcosim's fixed-step algorithm: a Jacobi exchange at the base step), compared with the
fmpy master's naive Jacobi loop at the same step.

Usage: python cosim_libcosim.py CAR.fmu BOOM.fmu [--t-end 1.0]
(the base step is the structure file's BaseStepSize, 1 ms)
"""

import argparse
import pathlib
import shutil
import sys
import tempfile

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from cosim import run  # noqa: E402

PROBES = {"car": ["body.heave", "body.pitch"], "boom": ["tip.position.y", "root.force.y"]}


def run_libcosim(car, boom, t_end):
    """Runs the OSP system structure with the two FMUs; returns (times, {name: samples})."""
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

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
        obs = CosimObserver.create_time_series()
        ex.add_observer(obs)
        refs = {}
        for name, probes in PROBES.items():
            i = ex.slave_index_from_instance_name(name)
            vr = {v.name.decode(): v.reference for v in ex.slave_variables(i)}
            for p in probes:
                refs[p] = (i, vr[p])
                obs.start_time_series(i, value_reference=vr[p],
                                      variable_type=CosimVariableType.REAL)
        assert ex.simulate_until(target_time=int(round(t_end * 1e9))), "libcosim failed"
        n = int(round(t_end / 1e-3)) + 1
        out, times = {}, None
        for p, (i, r) in refs.items():
            t, _, values = obs.time_series_real_samples(i, r, from_step=0, sample_count=n)
            out[p] = np.array(values)
            times = np.array(t) * 1e-9
    return times, out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("car")
    p.add_argument("boom")
    p.add_argument("--t-end", type=float, default=1.0)
    a = p.parse_args()
    t, lc = run_libcosim(a.car, a.boom, a.t_end)
    print(f"libcosim: {len(t)} samples to t = {t[-1]:.3f} s")
    rows, _, ok = run(a.car, a.boom, 1e-3, a.t_end, "jacobi")
    cols = {"body.heave": 1, "body.pitch": 2, "root.force.y": 7}
    for name, c in cols.items():
        ref = np.interp(t, rows[:, 0], rows[:, c])
        print(f"{name}: libcosim vs fmpy Jacobi max |Δ| {np.max(np.abs(lc[name] - ref)):.3e} "
              f"(range {np.ptp(rows[:, c]):.3e})")


if __name__ == "__main__":
    main()
