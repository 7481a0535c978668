"""Trajectories with and without the finite length of the annulus (validation.finite_length_trajectories)."""

import math

import numpy as np
import pytest

from dynamics.apparatus import Apparatus, preset
from dynamics.contact.full import steady_full_contact
from dynamics.contact.steady import steady_state
from lubrication import finite_length as fl
from lubrication.registry import kernel_model
from validation import finite_length_trajectories as flt

S, KAPPA_STAR = 0.25, 0.98


def _relative_gap(delta_over_a: float) -> float:
    """Locked speed of the module's formula against section 5's (5.10) on a distinguished-limit device."""
    ap = Apparatus.from_groups(s=S, upsilon=1.0, mu_ratio=1.5, delta_over_a=delta_over_a)
    reduced = steady_state(S, KAPPA_STAR, 0.5)  # psi = 0.5: locked (figure 8)
    assert reduced.phase == "locked"
    return flt.locked_speed(ap, kernel_model("closed-form"), KAPPA_STAR) / (ap.b * reduced.omega_b / ap.tau) - 1.0


def test_locked_speed_tends_to_section_5():
    """M g b^2 sin(alpha)/(eps* D) is the full model's locked rolling speed; section 5 is its leading order in
    delta/a, so the difference is first order: log-log slope 1 +- 0.05 over delta/a = 1e-3 .. 1e-4 (measured
    0.99; the first-order coefficient is only 0.02, so at 1e-2 the second order still bends the slope to 0.9)."""
    ratios = np.array([1e-3, 3e-4, 1e-4])
    gaps = np.abs([_relative_gap(r) for r in ratios])
    assert abs(np.polyfit(np.log(ratios), np.log(gaps), 1)[0] - 1.0) < 0.05


@pytest.mark.parametrize("ends", ["infinite", "open"])
def test_locked_speed_is_the_full_models_fixed_point(ends, monkeypatch):
    """The formula against Newton's method on the full contact equations
    (dynamics.contact.full.steady_full_contact, xtol 1e-12), steel apparatus, exact Stokes forces. Both
    sides take the same force model, so a coarse 5 x 5 factor table (built in a second) serves."""
    small = fl._build_table(5, 5, fl.ZETA_MIN, fl.X0)
    monkeypatch.setattr(fl, "factor_table", lambda: small)
    ap = preset("steel", nu=2e-4, alpha=math.radians(2.4))
    contact = flt.contact_of(ap)
    model = flt._model("stokes-exact", ends, ap)
    reduced = steady_state(ap.s, contact.kappa_star, contact.psi)
    fixed = steady_full_contact(ap, model, contact, True, [reduced.phi - ap.alpha, reduced.omega_a / ap.tau,
                                                           reduced.omega_b / ap.tau])
    assert flt.locked_speed(ap, model, contact.kappa_star) == pytest.approx(ap.b * fixed[2], rel=1e-9)


