"""What a value exchange with the beam's partner model still loses, measured: the partner scheme
of system.toml (naive exchange) with two host-side extrapolations that a value-exchanging host
could add (docs/coupling.md, "The partner model"):

- `--midpoint`: the car is given the beam's reaction extrapolated to the middle of the coming
  step, R + (R - R_prev)/2, held, instead of R held;
- `--jerk`: the beam is given, as its acceleration inputs' first derivative, the rate of the
  car's free acceleration a - G R_ref (the mount acceleration without the beam's reaction, from
  the car's mobility and reaction echo) over the last step.

    .venv/bin/python examples/vehicle/partner_extrapolation.py out/car.fmu out/boom.fmu \\
        [--midpoint] [--jerk] [--factor 100] [--steps 1e-3,5e-3,2e-2]

prints the largest energy residual over 2 s relative to its scale per step (the map's measure).
"""

import argparse
import pathlib

import numpy as np
from hybeam.cosim.master import _Links, _values
from hybeam.cosim.run import open_system
from hybeam.cosim.system import load

SYSTEM = pathlib.Path(__file__).resolve().parent / "system.toml"
ACC = ["root.acceleration.x", "root.acceleration.y", "root.angular_acceleration"]
CAR_ACC = ["mount.acceleration.x", "mount.acceleration.y", "mount.angular_acceleration"]
REACTION = ["fx", "fy", "mz"]
MOBILITY = [f"mount.mobility.{a}_{r}" for a in ("ax", "ay", "alphaz") for r in REACTION]
REFERENCE = [f"mount.reaction_reference.{r}" for r in REACTION]


def run(car, boom, h, factor, midpoint, jerk, t_end=2.0):
    """The largest |energy residual| / scale of the partner scheme at step `h` (or why it
    stopped)."""
    system = load(SYSTEM, {"car": car, "boom": boom})
    subs = open_system(system, "partner", [f"boom.mass_factor={factor}"])
    links = _Links(system.connections("partner"), system.order)
    reaction = [c for c in links.conns if c.dst == "car" and c.dst_var.startswith("beam.root")]
    e = system.energy
    probes = e.stored + e.supplied + e.dissipated
    nst, nsu = len(e.stored), len(e.supplied)
    prev, free_prev, e0, worst, scale = None, None, None, 0.0, 0.0
    try:
        for k in range(int(round(t_end / h))):
            vals = links.read(subs, links.conns)
            given = dict(vals)
            if midpoint and prev is not None:
                for c in reaction:
                    given[c] = vals[c] + 0.5 * (vals[c] - prev[c])
            prev = vals
            links.write(subs, given)
            if jerk:
                v = subs["car"].get(CAR_ACC + MOBILITY + REFERENCE)
                g = np.reshape(v[3:12], (3, 3))
                free = np.array(v[:3]) - g @ np.array(v[12:15])
                if free_prev is not None:
                    subs["boom"].set_rates(ACC, (free - free_prev) / h)
                free_prev = free
            for n in system.order:
                subs[n].step(k * h, h)
            v = _values(subs, probes)
            if e0 is None:
                e0 = v[:nst]
            d = [a - b for a, b in zip(v[:nst], e0, strict=True)]
            supplied, dissipated = sum(v[nst : nst + nsu]), sum(v[nst + nsu :])
            residual = sum(d) - supplied + dissipated
            scale = max(scale, sum(abs(x) for x in d) + abs(supplied) + abs(dissipated))
            worst = max(worst, abs(residual))
            if not worst < system.energy.divergence:
                return f"diverged at {k * h:.3f} s"
    except RuntimeError as ex:
        return f"stopped: {ex}"
    finally:
        for s in subs.values():
            s.close()
    return f"{worst / scale:.2e}"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("car")
    p.add_argument("boom")
    p.add_argument("--midpoint", action="store_true")
    p.add_argument("--jerk", action="store_true")
    p.add_argument("--factor", type=float, default=100.0)
    p.add_argument("--steps", default="1e-3,5e-3,2e-2")
    a = p.parse_args()
    for h in (float(x) for x in a.steps.split(",")):
        print(f"h = {h:g} s: {run(a.car, a.boom, h, a.factor, a.midpoint, a.jerk)}", flush=True)


if __name__ == "__main__":
    main()
