"""Two linear oscillators coupled through the interface of the car and the mounted beam, each a
`Subsystem` integrated by the generalized-α method (Chung & Hulbert 1993), one step per
communication step.

- `Carrier` (the car): mass m1 on a spring k1 to the ground; input `force`, the force of the
  support on the carried body (the carrier feels its negative), value and rate over the step;
  outputs `position`, `velocity`, `acceleration` (the method's acceleration variables).
- `Carried` (the mounted beam): a base mass m0 moving rigidly with the carrier and a mass m2 on
  a spring k2 to it; inputs the base `position`, `velocity`, `acceleration` at the start of a
  step and the acceleration's rate, from which it integrates the base path with the Newmark
  formulas (as the beam FMU integrates its mount path from the accelerations); output `force`
  = m0 a_base + k2 (x_base − x2), the support's force on it (direct feedthrough of the
  acceleration: apparent mass m0).

The monolithic reference (`monolithic`) solves the same equations in one system: the carrier's
equation with the force at n+1−α_f, the carried mass's, and the force's definition at n+1.
"""

import numpy as np
from hybeam.cosim.subsystem import Subsystem


def coefficients(rho_inf):
    am = (2 * rho_inf - 1) / (rho_inf + 1)
    af = rho_inf / (rho_inf + 1)
    gamma = 0.5 - am + af
    beta = 0.25 * (1 - am + af) ** 2
    return am, af, gamma, beta


class _Galpha(Subsystem):
    input_derivative_order = 1
    can_rollback = True
    provides_jacobian = True

    def __init__(self, rho_inf, state, inputs):
        self.c = coefficients(rho_inf)
        self.s = dict(state)
        self.u = dict(inputs)
        self.rate = {k: 0.0 for k in inputs}

    def names(self, causality):
        return list(self.u) if causality == "input" else self.OUTPUTS

    def get(self, names):
        return np.array([self.output(n) for n in names])

    def set(self, names, values):
        for n, v in zip(names, values, strict=True):
            self.u[n] = float(v)

    def set_rates(self, names, rates):
        for n, v in zip(names, rates, strict=True):
            self.rate[n] = float(v)

    def save(self):
        return (dict(self.s), dict(self.u), dict(self.rate))

    def restore(self, state):
        self.s, self.u, self.rate = (dict(x) for x in state)

    def newmark(self, x, v, a, a_new, h):
        _, _, gamma, beta = self.c
        return (
            x + h * v + h * h * ((0.5 - beta) * a + beta * a_new),
            v + h * ((1 - gamma) * a + gamma * a_new),
        )


class Carrier(_Galpha):
    OUTPUTS = ["position", "velocity", "acceleration", "energy"]

    def __init__(self, m1, k1, rho_inf, x0, v0, a0, f0):
        super().__init__(rho_inf, {"x": x0, "v": v0, "a": a0}, {"force": f0})
        self.m1, self.k1 = m1, k1

    def output(self, n):
        if n == "energy":
            return 0.5 * self.m1 * self.s["v"] ** 2 + 0.5 * self.k1 * self.s["x"] ** 2
        return {"position": self.s["x"], "velocity": self.s["v"], "acceleration": self.s["a"]}[n]

    def step(self, t, h):
        am, af, gamma, beta = self.c
        x, v, a = self.s["x"], self.s["v"], self.s["a"]
        f0 = self.u["force"]
        f1 = f0 + self.rate["force"] * h
        xp = x + h * v + h * h * (0.5 - beta) * a
        d = self.m1 * (1 - am) + self.k1 * (1 - af) * beta * h * h
        a1 = -(self.m1 * am * a + self.k1 * ((1 - af) * xp + af * x) + (1 - af) * f1 + af * f0) / d
        x1, v1 = self.newmark(x, v, a, a1, h)
        self.s = {"x": x1, "v": v1, "a": a1}
        self.rate = {k: 0.0 for k in self.rate}

    def jacobian(self, outputs, inputs):
        return np.zeros((len(outputs), len(inputs)))


class Carried(_Galpha):
    OUTPUTS = ["force", "position", "energy"]

    def __init__(self, m0, m2, k2, rho_inf, base, x2, v2, a2):
        super().__init__(
            rho_inf,
            {"x": x2, "v": v2, "a": a2},
            dict(zip(["position", "velocity", "acceleration"], base, strict=True)),
        )
        self.m0, self.m2, self.k2 = m0, m2, k2

    def output(self, n):
        if n == "force":
            return self.m0 * self.u["acceleration"] + self.k2 * (self.u["position"] - self.s["x"])
        if n == "energy":  # the base body moves with the base
            return (
                0.5 * self.m0 * self.u["velocity"] ** 2
                + 0.5 * self.m2 * self.s["v"] ** 2
                + 0.5 * self.k2 * (self.u["position"] - self.s["x"]) ** 2
            )
        return self.s["x"]

    def step(self, t, h):
        am, af, gamma, beta = self.c
        xb, vb, ab = self.u["position"], self.u["velocity"], self.u["acceleration"]
        ab1 = ab + self.rate["acceleration"] * h
        xb1, vb1 = self.newmark(xb, vb, ab, ab1, h)
        x, v, a = self.s["x"], self.s["v"], self.s["a"]
        xp = x + h * v + h * h * (0.5 - beta) * a
        d = self.m2 * (1 - am) + self.k2 * (1 - af) * beta * h * h
        a1 = -(self.m2 * am * a - self.k2 * ((1 - af) * (xb1 - xp) + af * (xb - x))) / d
        x1, v1 = self.newmark(x, v, a, a1, h)
        self.s = {"x": x1, "v": v1, "a": a1}
        # the base at the end of its path (a host setting the inputs again re-anchors it)
        self.u = {"position": xb1, "velocity": vb1, "acceleration": ab1}
        self.rate = {k: 0.0 for k in self.rate}

    def jacobian(self, outputs, inputs):
        j = np.zeros((len(outputs), len(inputs)))
        for i, o in enumerate(outputs):
            for k, n in enumerate(inputs):
                if o == "force":
                    j[i, k] = {"acceleration": self.m0, "position": self.k2}.get(n, 0.0)
        return j


def consistent_start(m0, m1, m2, k1, k2, x1, x2):
    """Accelerations and interface force of the continuous system at rest at (x1, x2)."""
    a1 = (-k1 * x1 - k2 * (x1 - x2)) / (m1 + m0)
    a2 = k2 * (x1 - x2) / m2
    return a1, a2, m0 * a1 + k2 * (x1 - x2)


def monolithic(m0, m1, m2, k1, k2, rho_inf, h, n, x1, x2):
    """The coupled equations by the generalized-α method in one system: rows (x1, x2, F)."""
    am, af, gamma, beta = coefficients(rho_inf)
    a1, a2, f = consistent_start(m0, m1, m2, k1, k2, x1, x2)
    v1 = v2 = 0.0
    out = [(x1, x2, f)]
    bh = beta * h * h
    for _ in range(n):
        p1 = x1 + h * v1 + h * h * (0.5 - beta) * a1
        p2 = x2 + h * v2 + h * h * (0.5 - beta) * a2
        # unknowns a1', a2', F'; x' = p + βh² a'
        A = np.array(
            [
                [m1 * (1 - am) + k1 * (1 - af) * bh, 0.0, 1 - af],
                [-k2 * (1 - af) * bh, m2 * (1 - am) + k2 * (1 - af) * bh, 0.0],
                [m0 + k2 * bh, -k2 * bh, -1.0],
            ]
        )
        b = np.array(
            [
                -(m1 * am * a1 + k1 * ((1 - af) * p1 + af * x1) + af * f),
                -(m2 * am * a2 - k2 * ((1 - af) * (p1 - p2) + af * (x1 - x2))),
                -k2 * (p1 - p2),
            ]
        )
        n1, n2, f = np.linalg.solve(A, b)
        x1n, v1 = (
            x1 + h * v1 + h * h * ((0.5 - beta) * a1 + beta * n1),
            v1 + h * ((1 - gamma) * a1 + gamma * n1),
        )
        x2n, v2 = (
            x2 + h * v2 + h * h * ((0.5 - beta) * a2 + beta * n2),
            v2 + h * ((1 - gamma) * a2 + gamma * n2),
        )
        x1, x2, a1, a2 = x1n, x2n, n1, n2
        out.append((x1, x2, f))
    return np.array(out)


def naive_matrix(m0, m1, m2, k1, k2, rho_inf, h):
    """The naive (Jacobi, held inputs) loop's one-step map z → G z, written from the
    equations above: z = (x1, v1, a1, x2, v2, a2, xb, vb, ab), (xb, vb, ab) the carried body's
    base at the end of its last path (its force output is computed with it)."""
    am, af, gamma, beta = coefficients(rho_inf)
    G = np.zeros((9, 9))
    for i in range(9):
        x1, v1, a1, x2, v2, a2, xb, vb, ab = np.eye(9)[i]
        f = m0 * ab + k2 * (xb - x2)  # read before the exchange
        # carrier with the force held
        p = x1 + h * v1 + h * h * (0.5 - beta) * a1
        n1 = -(m1 * am * a1 + k1 * ((1 - af) * p + af * x1) + f) / (
            m1 * (1 - am) + k1 * (1 - af) * beta * h * h
        )
        # carried with the base (x1, v1, a1) and its acceleration held
        bx = x1 + h * v1 + h * h * 0.5 * a1
        bv = v1 + h * a1
        q = x2 + h * v2 + h * h * (0.5 - beta) * a2
        n2 = -(m2 * am * a2 - k2 * ((1 - af) * (bx - q) + af * (x1 - x2))) / (
            m2 * (1 - am) + k2 * (1 - af) * beta * h * h
        )
        G[:, i] = [
            x1 + h * v1 + h * h * ((0.5 - beta) * a1 + beta * n1),
            v1 + h * ((1 - gamma) * a1 + gamma * n1),
            n1,
            x2 + h * v2 + h * h * ((0.5 - beta) * a2 + beta * n2),
            v2 + h * ((1 - gamma) * a2 + gamma * n2),
            n2,
            bx,
            bv,
            a1,
        ]
    return G
