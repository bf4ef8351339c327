"""The sweep's signal summaries against closed forms (python/hybeam/sweep/run.py)."""

import numpy as np
from hybeam.sweep.run import frequency, settling


def test_frequency_of_a_sine_from_its_mean_crossings():
    t = np.linspace(0.0, 2.0, 2001)
    assert abs(frequency(t, 5.0 + np.sin(2 * np.pi * 3.3 * t + 0.3)) / 3.3 - 1) < 1e-6
    assert np.isnan(frequency(t, t))  # no oscillation


def test_settling_time_of_a_first_order_step_response():
    """1 - exp(-t/tau) enters the 2 % band at tau ln 50."""
    t = np.linspace(0.0, 2.0, 20001)
    tau = 0.1
    assert abs(settling(t, 1 - np.exp(-t / tau)) - tau * np.log(50)) < 2e-4
    assert settling(t, np.ones_like(t)) == 0.0
