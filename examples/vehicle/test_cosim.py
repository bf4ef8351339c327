"""The coupled car + boom co-simulation in fmpy (examples/vehicle/cosim.py), each check against
an independent reference: the same coupled run at a communication step 8x finer (order of
convergence), the coupled energy balance (a conservation law), and the naive loop against the
loop closed with the FMUs' directional derivatives on a heavy boom."""

import numpy as np

from cosim import run

T_END = 0.8  # s: over the bump (front wheel at 0.38 s, rear at 0.65 s)


def test_coupled_solution_converges_at_second_order_and_closes_energy(fmus):
    car, boom = fmus
    ref, _, ok = run(car, boom, 2.5e-4, T_END, "newton", derivatives=True)
    assert ok
    errors = []
    for h in (2e-3, 1e-3):
        rows, res, ok = run(car, boom, h, T_END, "newton", derivatives=True)
        assert ok
        r = ref[:: int(round(h / 2.5e-4))][: len(rows)]
        errors.append(np.max(np.abs(rows[:, 10] - r[:, 10])))
        scale = np.max(np.abs(rows[:, 11] - rows[0, 11])) + np.max(np.abs(rows[:, 13]))
        assert np.max(np.abs(res)) < 1e-3 * scale, (h, np.max(np.abs(res)), scale)
    order = np.log2(errors[0] / errors[1])
    print(f"boom tip errors {errors}, order {order:.2f}")
    assert order > 1.7, errors


def test_directional_derivatives_keep_a_heavy_boom_stable_where_the_naive_loop_is_not(fmus):
    car, boom = fmus
    _, naive, ok_naive = run(car, boom, 5e-4, 1.0, "jacobi", 10.0)
    _, newton, ok = run(car, boom, 5e-4, 1.0, "newton", 10.0)
    print(f"energy residual: naive {np.max(np.abs(naive)):.3e} J, newton {np.max(np.abs(newton)):.3e} J")
    assert ok
    assert np.max(np.abs(newton)) < 2e-2 * 1.45e3
    assert not ok_naive or np.max(np.abs(naive)) > 100 * np.max(np.abs(newton))
