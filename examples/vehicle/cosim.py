"""Co-simulation of the pitch-plane car (car.fmu) and a mounted hybeam boom (boom.fmu) in fmpy.

The car's mount.* outputs drive the beam's root.* inputs (pose, velocities, accelerations);
the beam's reaction root.force.{x,y}, root.moment.z (support on the beam) goes back to the
car's beam.root.* inputs (the car applies its negative at the roof mount).

Coupling schemes (--scheme), fixed communication step h:
  jacobi    the naive loop: both FMUs exchange their current outputs and step in parallel.
  newton    at every communication point the algebraic loop of the direct feedthrough (the
            beam's reaction depends on the mount accelerations, the car's mount accelerations
            on the reaction) is closed exactly with both FMUs' fmi2GetDirectionalDerivative
            (the beam's apparent mass at the mount, the car's mobility): one linear solve, as
            both sides are linear in these inputs; then both step.
  interface the interface-mass loop (spatial.md §5.3): the car carries the beam's current rigid
            inertia (root.mass, root.center_of_mass.*, root.inertia.zz) as a payload at the
            mount, and gets only the reaction beyond the payload's (the beam's
            root.force_elastic, root.moment_elastic: its reaction minus the rigid reaction of
            that inertia at its mount motion); the exchange then lags the elastic part only.
  interface-newton  both: the car carries the payload, and the loop of the remaining
            feedthrough (the elastic outputs' directional derivatives: the beam's apparent
            mass minus the payload's) is closed as in newton.
With --derivatives the beam also gets the car's mount-acceleration rate and the car the
reaction's rate (backward differences over the last step) as first input derivatives.

Writes CSV (time, body heave/pitch, mount, reaction, beam tip relative to the mount, energies)
and a plot; prints the coupled energy balance:
  ΔE_car + ΔE_beam − W_road + D_car − W_drive   (E_beam = kinetic + strain + gravity potential;
  W_drive = ∫ F_x V dt, the work of the car's drive, which holds the forward speed V, on the
  beam)
which is zero for the exact coupled solution (the beam is undamped; its integrator's
numerical dissipation and the interface's exchange error remain).

Usage: python cosim.py CAR.fmu BOOM.fmu [--h 1e-3] [--t-end 1.5] [--scheme newton|jacobi]
                       [--density-factor F] [--out PREFIX]
"""

import argparse
import csv
import math
import shutil
import tomllib

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

MOUNT = ["position.x", "position.y", "angle", "velocity.x", "velocity.y",
         "angular_velocity", "acceleration.x", "acceleration.y", "angular_acceleration"]
REACTION = ["root.force.x", "root.force.y", "root.moment.z"]
INERTIA = ["root.mass", "root.center_of_mass.x", "root.center_of_mass.y", "root.inertia.zz"]
# the reaction beyond the rigid inertia's own (the beam FMU computes it at its mount motion)
ELASTIC = ["root.force_elastic.x", "root.force_elastic.y", "root.moment_elastic.z"]


class Fmu:
    """An FMU instance with value references by name."""

    def __init__(self, path, name):
        self.md = read_model_description(path)
        self.dir = extract(path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.slave = FMU2Slave(guid=self.md.guid, unzipDirectory=self.dir,
                               modelIdentifier=self.md.coSimulation.modelIdentifier,
                               instanceName=name)
        self.slave.instantiate()

    def get(self, names):
        return np.array(self.slave.getReal([self.vr[n] for n in names]))

    def set(self, names, values):
        self.slave.setReal([self.vr[n] for n in names], [float(x) for x in values])

    def jacobian(self, outs, ins):
        """∂outs/∂ins by fmi2GetDirectionalDerivative, one seed per input."""
        vo, vi = [self.vr[n] for n in outs], [self.vr[n] for n in ins]
        cols = []
        for k in range(len(ins)):
            seed = [0.0] * len(ins)
            seed[k] = 1.0
            cols.append(self.slave.getDirectionalDerivative(vo, vi, seed))
        return np.array(cols).T

    def close(self):
        self.slave.terminate()
        self.slave.freeInstance()
        shutil.rmtree(self.dir, ignore_errors=True)


def feed_car(car, boom, scheme):
    """Sets the car's beam inputs from the beam's outputs: its reaction, or with `interface`
    its rigid inertia as the car's payload and the reaction beyond the payload's
    (root.force_elastic, root.moment_elastic). Returns the beam's reaction."""
    f = boom.get(REACTION)
    if scheme.startswith("interface"):
        car.set(["beam." + n for n in INERTIA], boom.get(INERTIA))
        car.set(["beam." + n for n in REACTION], boom.get(ELASTIC))
    else:
        car.set(["beam." + n for n in REACTION], f)
    return f


def start(car_path, boom_path, density_factor=1.0, scheme="jacobi"):
    """Both FMUs initialized in their coupled static start; returns (car, boom)."""
    car, boom = Fmu(car_path, "car"), Fmu(boom_path, "boom")
    car_mount = ["mount." + n for n in MOUNT]
    beam_mount = ["root." + n for n in MOUNT]
    car_in = ["beam." + n for n in REACTION]
    for f in (car, boom):
        f.slave.setupExperiment(startTime=0.0)
        f.slave.enterInitializationMode()
    names = [n for n in boom.vr if n.endswith(".density")]
    if density_factor != 1.0:
        boom.set(names, [density_factor * x for x in boom.get(names)])
    # the beam starts in static equilibrium on the roof; the car in static equilibrium
    # under the beam's static reaction (the beam is re-anchored to the car's exact pose at
    # the first exchange: a rigid move, no impulse)
    boom.set(beam_mount, car.get(car_mount))  # pose and velocity: the beam rides along
    boom.slave.exitInitializationMode()
    feed_car(car, boom, scheme)
    car.slave.exitInitializationMode()
    # again on the car's settled pose (its static sag under the beam's weight)
    boom.slave.reset()
    boom.slave.setupExperiment(startTime=0.0)
    boom.slave.enterInitializationMode()
    if density_factor != 1.0:
        boom.set(names, [density_factor * x for x in boom.get(names)])
    boom.set(beam_mount, car.get(car_mount))
    boom.slave.exitInitializationMode()
    return car, boom


def coupling_ratio(car_path, boom_path, density_factor=1.0, scheme="jacobi"):
    """The exchange's amplification per step at the start: the spectral radius of Jb Jc (the
    partials of what the car is given by the mount accelerations times the car's mobility,
    both from fmi2GetDirectionalDerivative): the beam's apparent mass for the naive exchange,
    apparent minus rigid mass with interface mass (`interface`, the car then carrying the
    rigid inertia); the exchange is unstable above 1. Also returns the beam's mass
    (root.mass) and the diagonal of the reaction's partials (its apparent mass along x and y
    [kg] and in rotation [kg m²])."""
    car, boom = start(car_path, boom_path, density_factor, scheme)
    accelerations = ["root." + n for n in MOUNT[6:]]
    given = ELASTIC if scheme.startswith("interface") else REACTION
    jb = boom.jacobian(given, accelerations)
    jc = car.jacobian(["mount." + n for n in MOUNT[6:]], ["beam." + n for n in REACTION])
    rho = float(np.max(np.abs(np.linalg.eigvals(jb @ jc))))
    mass = float(boom.get(["root.mass"])[0])
    apparent = np.diag(boom.jacobian(REACTION, accelerations))
    car.close()
    boom.close()
    return rho, mass, apparent


def run(car_path, boom_path, h, t_end, scheme="newton", density_factor=1.0, derivatives=False,
        out=None):
    """Runs the coupled model; returns (rows, energy residual history, ok)."""
    car, boom = start(car_path, boom_path, density_factor, scheme)
    car_mount = ["mount." + n for n in MOUNT]
    beam_mount = ["root." + n for n in MOUNT]
    car_in = ["beam." + n for n in REACTION]
    with open(f"{car.dir}/resources/vehicle.toml", "rb") as fh:
        speed = tomllib.load(fh)["road"]["speed"]
    w_drive = 0.0  # work of the car's drive on the beam along x (the car's x is prescribed)
    e_beam = ["energy.kinetic", "energy.strain", "energy.potential"]
    rows, residual = [], []
    e0 = None
    prev_acc = None
    ok = True
    n = int(round(t_end / h))
    for k in range(n + 1):
        t = k * h
        m = car.get(car_mount)
        boom.set(beam_mount, m)
        if scheme in ("newton", "interface-newton"):
            # close the loop F = F0 + Jb (a − a_b), a = A0 + Jc (F − F_c) exactly (F: what
            # the car is given; with interface mass the reaction beyond the payload's)
            given = REACTION
            if scheme == "interface-newton":
                car.set(["beam." + n for n in INERTIA], boom.get(INERTIA))
                given = ELASTIC
            jb = boom.jacobian(given, beam_mount[6:])
            f0 = boom.get(given)
            jc = car.jacobian(car_mount[6:], car_in)
            fc = car.get(car_in)
            f = np.linalg.solve(np.eye(3) - jb @ jc, f0 - jb @ (jc @ fc))
            car.set(car_in, f)
            m = car.get(car_mount)
            boom.set(beam_mount[6:], m[6:])
        f = feed_car(car, boom, scheme)
        given = car.get(car_in)  # the reaction, or with interface mass its elastic part
        if derivatives and prev_acc is not None:
            rate = (m[6:] - prev_acc) / h
            boom.slave.setRealInputDerivatives([boom.vr[n] for n in beam_mount[6:]], [1, 1, 1],
                                               list(rate))
            car.slave.setRealInputDerivatives([car.vr[n] for n in car_in], [1, 1, 1],
                                              list((given - prev_given) / h))
        prev_acc, prev_given = m[6:].copy(), given
        ec = car.get(["energy.total", "energy.road_work", "energy.dissipated"])
        eb = boom.get(e_beam).sum()
        if e0 is None:
            e0 = (ec[0], eb)
        balance = (ec[0] - e0[0]) + (eb - e0[1]) - ec[1] + ec[2] - w_drive
        residual.append(balance)
        tip = boom.get(["tip.position.x", "tip.position.y"])
        rel = tip - m[:2]
        c, s = math.cos(m[2]), math.sin(m[2])
        rows.append([t, *car.get(["body.heave", "body.pitch"]), *m[:3], *f,
                     c * rel[0] + s * rel[1], -s * rel[0] + c * rel[1], ec[0], eb, ec[1], ec[2],
                     balance])
        if k == n:
            break
        if not (np.all(np.isfinite(f)) and abs(f[1]) < 1e7):
            ok = False
            break
        w_drive += f[0] * speed * h  # the reaction is held over the step on the car's side
        sb, sc = boom.slave.doStep(t, h), car.slave.doStep(t, h)
        if sb is not None and sb > 1 or sc is not None and sc > 1:
            ok = False
            break
    car.close()
    boom.close()
    if out:
        header = ["time", "body.heave", "body.pitch", "mount.x", "mount.y", "mount.angle",
                  "root.force.x", "root.force.y", "root.moment.z", "tip.rel.x", "tip.rel.y",
                  "energy.car", "energy.beam", "road_work", "dissipated", "energy_residual"]
        with open(out + ".csv", "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows(rows)
    return np.array(rows), np.array(residual), ok


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    t = rows[:, 0]
    ax[0].plot(t, 1e3 * (rows[:, 1] - rows[0, 1]), label="body heave from the static start [mm]")
    ax[0].plot(t, 1e3 * (rows[:, 2] - rows[0, 2]), label="body pitch from the static start [mrad]")
    ax[0].legend()
    ax[1].plot(t, 1e3 * rows[:, 10], label="boom tip deflection in the mount frame [mm]")
    ax[1].legend()
    ax[2].plot(t, rows[:, 7], label="root.force.y [N]")
    ax[2].plot(t, rows[:, 8], label="root.moment.z [N m]")
    ax[2].legend()
    ax[2].set_xlabel("time [s]")
    fig.suptitle("car over a 5 cm bump at 10 m/s with a 3 m roof boom (fmpy, hybeam FMU)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("car")
    p.add_argument("boom")
    p.add_argument("--h", type=float, default=1e-3)
    p.add_argument("--t-end", type=float, default=1.5)
    p.add_argument("--scheme", choices=["newton", "jacobi", "interface", "interface-newton"],
                   default="newton")
    p.add_argument("--density-factor", type=float, default=1.0)
    p.add_argument("--derivatives", action="store_true")
    p.add_argument("--out", default="out/vehicle")
    a = p.parse_args()
    rows, res, ok = run(a.car, a.boom, a.h, a.t_end, a.scheme, a.density_factor, a.derivatives,
                        a.out)
    plot(rows, a.out + ".png")
    scale = np.max(np.abs(rows[:, 11] - rows[0, 11])) + np.max(np.abs(rows[:, 13]))
    print(f"{'ok' if ok else 'FAILED'}: {len(rows)} rows to {a.out}.csv and {a.out}.png; "
          f"energy residual max {np.max(np.abs(res)):.3e} J of {scale:.3e} J")


if __name__ == "__main__":
    main()
