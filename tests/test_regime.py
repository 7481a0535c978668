"""The regime of a run (dynamics.regime.classify) and the numbers it is read from (late_half), on constructed runs."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from dynamics.regime import SHORTEST_SETTLED, classify, late_half


@pytest.mark.parametrize("cycles", [0.25, 3.0, 7.5])
def test_reversals_turns_and_spreads_of_a_known_swing(cycles):
    """phi = pi + 0.3 sin(2 pi cycles t / T) on [0, T]: its extrema in the second half are where
    cycles t / T - 1/4 is a multiple of 1/2, strictly inside (T/2, T); phi's spread there is 0.6
    as soon as a maximum and a minimum are both in it; a steady drift of a quarter turn shows as turns."""
    t = np.linspace(0.0, 10.0, 20_001)
    swing = 0.3 * np.sin(2.0 * math.pi * cycles * t / t[-1])
    late, turns, reversals, phi_spread, gap_spread, omega_b_spread = late_half(
        t, math.pi + swing, np.exp(-t), 2.0 + 0.5 * t)
    assert t[late] == 5.0
    extrema = [k for k in range(-2, 40) if cycles / 2 < k / 2 + 0.25 < cycles]
    assert reversals == len(extrema)
    assert turns == pytest.approx((swing[-1] - swing[late]) / (2.0 * math.pi), abs=1e-15)
    if len(extrema) >= 2:
        assert phi_spread == pytest.approx(0.6, rel=1e-6)  # sampled every 5e-4 T: within 1e-6 of the peaks
    assert gap_spread == pytest.approx(math.exp(-5.0) - math.exp(-10.0), rel=1e-14)
    assert omega_b_spread == pytest.approx(2.5, rel=1e-14)


def test_a_run_of_one_row_is_all_second_half():
    assert late_half([0.0], [1.0], [0.5], [0.0]) == (0, 0.0, 0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("columns", [([], [], [], []), ([0.0, 1.0], [1.0], [0.5, 0.5], [0.0, 0.0])])
def test_empty_or_unequal_columns_are_refused(columns):
    with pytest.raises(ValueError, match="one length, at least 1"):
        late_half(*columns)


def _trajectory(t_tau, phi, kappa, omega_b, tau=1.0):
    """A trajectory as classify reads it (columns in units of tau)."""
    kappa = np.asarray(kappa, dtype=float)
    columns = {"t_tau": np.asarray(t_tau, dtype=float), "phi": np.asarray(phi, dtype=float), "kappa": kappa,
               "one_minus_kappa": 1.0 - kappa, "omega_b": np.asarray(omega_b, dtype=float) / tau}
    return SimpleNamespace(columns=columns, tau=tau, status="completed", event="")


@pytest.mark.parametrize(("duration", "expected"), [(1e-12, "transient"), (1.99, "transient"),
                                                    (2.0, "steady rolling"), (50.0, "steady rolling")])
def test_constant_motion_is_steady_only_over_a_run_long_enough_to_show_it(duration, expected):
    """Gap, angle and rolling rate constant: steady rolling, unless the run is too short for anything to change."""
    assert SHORTEST_SETTLED == 2.0  # the durations above straddle it
    t = np.linspace(0.0, duration, 101)
    regime, evidence = classify(_trajectory(t, np.full_like(t, 0.3), np.full_like(t, 0.9), np.full_like(t, 0.2)))
    assert regime == expected
    assert evidence["one_minus_kappa_relative_spread_late"] == 0.0  # the spreads are reported either way


@pytest.mark.parametrize(("duration", "swings", "expected"), [(1.0, 0.0, "transient"), (10.0, 0.0, "sedimenting"),
                                                              (1.0, 1.0, "rocking"), (10.0, 1.0, "rocking")])
def test_sedimenting_needs_a_settled_run_and_rocking_its_swings(duration, swings, expected):
    """Near contact and without turns: two reversals of phi are rocking however short the run; no swing is
    sedimenting only over a run long enough for a swing to have shown."""
    t = np.linspace(0.0, duration, 2001)
    phi = 0.1 * np.sin(2.0 * math.pi * 2.6 * t / duration) * swings  # extrema at phase 3.5 pi and 4.5 pi after t/2
    kappa = 0.96 + 0.03 * t / duration
    regime, evidence = classify(_trajectory(t, phi, kappa, np.zeros_like(t)))
    assert (regime, evidence["phi_reversals_late"]) == (expected, 2 * swings)
