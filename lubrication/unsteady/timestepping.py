r"""Variable-step IMEX BDF2, its explicit predictor and its local error estimate.

Implicit part. With the step h = t_{n+1} - t_n and the previous one h' = t_n - t_{n-1},
r = h/h', the derivative of the quadratic through (t_{n-1}, t_n, t_{n+1}) at t_{n+1} is

    y'_{n+1} ~ (alpha_0 y_{n+1} + alpha_1 y_n + alpha_2 y_{n-1}) / h,
    alpha_0 = (1 + 2 r)/(1 + r),  alpha_1 = -(1 + r),  alpha_2 = r^2/(1 + r);

the first step is implicit Euler (alpha = 1, -1, 0).

Explicit part. The convective term is extrapolated to t_{n+1} linearly,
N* = (1 + r) N_n - r N_{n-1} (N_0 on the first step): second order, as BDF2.

Local error. For the interpolation error of the quadratic, p'(t_{n+1}) - y'(t_{n+1})
= -(y'''/6) h (h + h'), so the step's local error (Jacobian neglected) is
e = -(y'''/6) h^2 (h + h')^2 / (2 h + h'). The explicit predictor y^P, the quadratic
through (t_{n-2}, t_{n-1}, t_n) extrapolated to t_{n+1}, has the error
-(y'''/6) h (h + h')(h + h' + h''), so

    e = -E (y_{n+1} - y^P),   E = h (h + h') / (2 h + h') / [h + h' + h'' - h (h + h') / (2 h + h')]

(E = 2/7 for constant steps). With only two levels the predictor is the linear
extrapolation, and y_{n+1} - y^P itself (first order, an overestimate) is the
estimate: the second step is controlled conservatively. The step size follows
h_new = h min(fac_max, max(fac_min, safety err^(-1/3))).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Bdf", "bdf", "error_constant", "extrapolation", "next_step", "predictor_weights"]


@dataclass(frozen=True)
class Bdf:
    """BDF coefficients of one step: y' = (alpha0 y_new + alpha1 y_n + alpha2 y_{n-1}) / dt."""

    alpha0: float
    alpha1: float
    alpha2: float
    dt: float

    def derivative(self, new, now, before):
        """The BDF derivative of a quantity from its three levels."""
        return (self.alpha0 * new + self.alpha1 * now + self.alpha2 * before) / self.dt

    def history(self, now, before):
        """The part of the derivative known before the step: (alpha1 y_n + alpha2 y_{n-1}) / dt."""
        return (self.alpha1 * now + self.alpha2 * before) / self.dt

    @property
    def c0(self) -> float:
        """alpha0 / dt, the coefficient of the new level."""
        return self.alpha0 / self.dt


def bdf(dt: float, dt_prev: float | None) -> Bdf:
    """BDF2 coefficients for the step ``dt`` after ``dt_prev`` (implicit Euler if None)."""
    if dt_prev is None:
        return Bdf(1.0, -1.0, 0.0, dt)
    r = dt / dt_prev
    return Bdf((1.0 + 2.0 * r) / (1.0 + r), -(1.0 + r), r * r / (1.0 + r), dt)


def extrapolation(dt: float, dt_prev: float | None) -> tuple[float, float]:
    """Weights (w_n, w_{n-1}) of the linear extrapolation to t_{n+1}."""
    if dt_prev is None:
        return 1.0, 0.0
    r = dt / dt_prev
    return 1.0 + r, -r


def predictor_weights(dt: float, steps: tuple[float, ...]) -> tuple[float, ...]:
    """Weights of the explicit predictor at t_{n+1} from levels n, n-1, (n-2).

    ``steps`` = (h', h'') are the previous step sizes (one or two of them):
    Lagrange extrapolation through the points 0, -h', -h' - h'' to t = dt.
    """
    nodes = [0.0]
    for h in steps:
        nodes.append(nodes[-1] - h)
    out = []
    for i, ti in enumerate(nodes):
        w = 1.0
        for j, tj in enumerate(nodes):
            if j != i:
                w *= (dt - tj) / (ti - tj)
        out.append(w)
    return tuple(out)


def error_constant(dt: float, steps: tuple[float, ...]) -> float:
    """E with local error = E |y_{n+1} - y^P| (module docstring); 1 with a linear predictor."""
    if len(steps) < 2:
        return 1.0
    h, h1, h2 = dt, steps[0], steps[1]
    bdf_part = h * (h + h1) / (2.0 * h + h1)
    return bdf_part / (h + h1 + h2 - bdf_part)


def next_step(dt: float, err: float, *, safety: float = 0.8, fac_min: float = 0.2, fac_max: float = 2.0) -> float:
    """The next step size for the error ratio ``err`` (1 = at the tolerance), third-order law."""
    if err <= 0.0:
        return dt * fac_max
    return dt * min(fac_max, max(fac_min, safety * err ** (-1.0 / 3.0)))
