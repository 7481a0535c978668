"""numba kernels of the cavitating Reynolds solver; the formulation is in :mod:`lubrication.cavitation`.

They work on the cell integrals of :func:`lubrication.reynolds_kernels.cell_integrals`
and with phi = p/(12 mu a) measured from the reference pressure: y_j = phi_j - phi_ref,
y_0 = 0 at the feed node, and the cavitation level y_cav = (p_cav - p_ref)/(12 mu a) <= 0.
"""

from __future__ import annotations

import numpy as np

from numerics.jit import jit

from .reynolds_kernels import (
    ECCENTRIC,
    H1,
    H2,
    H3,
    N_INTEGRALS,
    OH2,
    OH3,
    OQH3,
    QH2,
    QH3,
    SH2,
    SH3,
    SQH3,
    cell_integrals,
    full_film,
)

# Cavitation models, in the order of lubrication.cavitation.CAVITATION_MODELS.
NONE, HALF_SOMMERFELD, SWIFT_STIEBER, JFO = 0, 1, 2, 3
# What a node's unknown is in the active-set iteration: the pressure excess x (full film),
# the film fraction F (JFO cavity), or the mass residual w (Swift-Stieber cavity, and a JFO
# cavity node whose F does not enter any balance).
FULL, FRACTION, SLACK = 0, 1, 2
# Violations below this fraction of the problem's scale are rounding, not a reason to switch.
SWITCH_TOLERANCE = 1e-12
# Passes per grid level with the full Newton switching, before one node at a time.
SAFE_PASSES = 8
# The smallest step of the squeeze continuation before the solve is declared failed.
MIN_CONTINUATION_STEP = 1.0 / 4096
# The active-set hierarchy coarsens down to this many cells.
COARSEST_LEVEL = 16


@jit
def tridiagonal_solve(lower, diag, upper, rhs):
    """Solve a tridiagonal system in place by elimination with partial pivoting (as LAPACK gtsv).

    ``lower[i]`` = A[i+1, i], ``diag[i]`` = A[i, i], ``upper[i]`` = A[i, i+1]; all four
    arrays are overwritten and ``rhs`` returns the solution. Returns False if a pivot
    is exactly zero (a singular matrix).
    """
    n = diag.size
    second = np.zeros(n)  # fill-in of the second superdiagonal from row swaps
    for i in range(n - 1):
        if abs(diag[i]) >= abs(lower[i]):
            if diag[i] == 0.0:
                return False
            fact = lower[i] / diag[i]
            diag[i + 1] -= fact * upper[i]
            rhs[i + 1] -= fact * rhs[i]
        else:
            fact = diag[i] / lower[i]
            diag[i] = lower[i]
            temp = diag[i + 1]
            diag[i + 1] = upper[i] - fact * temp
            if i < n - 2:
                second[i] = upper[i + 1]
                upper[i + 1] = -fact * second[i]
            upper[i] = temp
            temp = rhs[i]
            rhs[i] = rhs[i + 1]
            rhs[i + 1] = temp - fact * rhs[i + 1]
    if diag[n - 1] == 0.0:
        return False
    rhs[n - 1] /= diag[n - 1]
    if n > 1:
        rhs[n - 2] = (rhs[n - 2] - upper[n - 2] * rhs[n - 1]) / diag[n - 2]
    for i in range(n - 3, -1, -1):
        rhs[i] = (rhs[i] - upper[i] * rhs[i + 1] - second[i] * rhs[i + 2]) / diag[i]
    return True


@jit
def _cell_coefficients(integrals, half_u):
    """Conductance g = 1/G, Couette flux k = (U/2) A/G and squeeze level <Q> = B/G of each cell."""
    g = 1.0 / integrals[:, H3]
    return g, half_u * integrals[:, H2] * g, integrals[:, QH3] * g


@jit
def balance(integrals, half_u, y, film, upwind_left, r_out):
    """Mass residual of every node: content flux out of its dual cell minus flux in, plus F a h_t.

    R_j = qbar_j - qbar_{j-1} + F_j (<Q>_j - <Q>_{j-1}) with the cell flux
    qbar_j = F_up k_j - g_j (y_{j+1} - y_j); zero where the film balances.
    """
    n = y.size
    g, k, qm = _cell_coefficients(integrals, half_u)
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        jp = j + 1 if j < n - 1 else 0
        f_cell = film[j] if upwind_left else film[jp]
        f_prev = film[jm] if upwind_left else film[j]
        out = f_cell * k[j] - g[j] * (y[jp] - y[j])
        inflow = f_prev * k[jm] - g[jm] * (y[j] - y[jm])
        r_out[j] = out - inflow + film[j] * (qm[j] - qm[jm])


@jit
def _film_integrals(integrals, half_u, u_a, u_b, y, weight, film):
    """oint phi' sin, oint phi' omega and the torque sum of a film described cell by cell.

    In cell j the pressure is the full-film profile through the nodal values
    (flux constant c_j = ((U/2) A_j + B_j - (y_{j+1} - y_j))/G_j), counted with
    ``weight[j]`` (1 full, 0 cavitated, the fraction above p_cav for a truncated
    cell); the Couette shear is counted with the film fraction upwind of the cell. In a
    steady cavity F_j = C/k_j is the fraction of the liquid crossing cell j, so the
    upwind value belongs to the cell; the mean of F_j and F_(j+1) is half a cell off, a
    first-order error wherever the cell integral of 1/h varies from cell to cell (the
    grid uniform in theta: the torque converged as N^-1 with it, as N^-2 upwind).
    """
    n = y.size
    i_sin = i_chi = i_press = i_couette = 0.0
    for j in range(n):
        jp = j + 1 if j < n - 1 else 0
        row = integrals[j]
        i_couette += (film[j] if half_u >= 0.0 else film[jp]) * row[H1]
        if weight[j] == 0.0:
            continue
        c = (half_u * row[H2] + row[QH3] - (y[jp] - y[j])) / row[H3]
        i_sin += weight[j] * (half_u * row[SH2] + row[SQH3] - c * row[SH3])
        i_chi += weight[j] * (half_u * row[OH2] + row[OQH3] - c * row[OH3])
        i_press += weight[j] * (half_u * row[H1] + row[QH2] - c * row[H2])
    return i_sin, i_chi, (u_b - u_a) * i_couette - 6.0 * i_press


@jit
def _active_set(integrals, half_u, model, y_cav, state, y, film, max_iterations):
    """The primal-dual active-set (semismooth Newton) iteration for Swift-Stieber and JFO.

    ``state`` holds each node's first state (FULL or not) and leaves with the
    last; ``y`` enters as the full-film solution (y_0 = 0), which sets the
    switching scales, and leaves as the solution; ``film`` receives F. Each pass solves
    the tridiagonal balance R_j = 0 of nodes 1..N-1 for one unknown per node (x,
    F or w by its state) and switches the nodes whose solution violates a sign
    condition. Returns the number of passes, or -1 if the set still changed
    after ``max_iterations``.
    """
    n = y.size
    g, k, qm = _cell_coefficients(integrals, half_u)
    s = np.empty(n)
    for j in range(n):
        s[j] = qm[j] - qm[j - 1 if j > 0 else n - 1]
    upwind_left = half_u >= 0.0
    x_ref = -y_cav  # the feed node's pressure excess, >= 0
    # scales for the switching tolerances: pressure excess, and flux (all terms of a balance)
    x_scale = x_ref
    for j in range(n):
        x_scale = max(x_scale, abs(y[j] - y_cav))
    w_scale = 0.0
    for j in range(n):
        w_scale = max(w_scale, abs(k[j]) + abs(s[j]) + 2.0 * g[j] * x_scale)
    # a problem without any pressure or flux scale has nothing to switch; keep the divisions finite
    x_scale = max(x_scale, 1e-300)
    w_scale = max(w_scale, 1e-300)
    f_columns = 0.0
    for j in range(n):
        f_columns = max(f_columns, abs(k[j]) + abs(s[j]))
    for j in range(1, n):
        if state[j] != FULL:
            state[j] = FRACTION if model == JFO else SLACK
    m = n - 1
    lower, diag, upper, rhs = np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    violation, empty = np.zeros(n), np.zeros(n)
    flips = np.zeros(n, dtype=np.int64)  # switches of each node, to recognise a node that cycles
    for iteration in range(1, max_iterations + 1):
        lower[:] = 0.0
        diag[:] = 0.0
        upper[:] = 0.0
        rhs[:] = 0.0
        for j in range(1, n):
            if model == JFO and state[j] != FULL:
                # a cavity node whose F enters no balance (no Couette flux, no squeeze) keeps F = 0
                column = abs(k[j] if upwind_left else k[j - 1]) + abs(s[j])
                state[j] = FRACTION if column > SWITCH_TOLERANCE * f_columns else SLACK
        # every node's contribution to the balances of rows j-1, j, j+1 (node 0 is the known feed)
        for j in range(n):
            jm = j - 1 if j > 0 else n - 1
            jp = j + 1 if j < n - 1 else 0
            # the pressure excess x_j: Poiseuille fluxes to both neighbours
            c_prev, c_self, c_next = -g[jm], g[j] + g[jm], -g[j]
            if state[j] == FULL:
                if j == 0:
                    _add_known(rhs, j, jm, jp, c_prev * x_ref, c_self * x_ref, c_next * x_ref)
                else:
                    _add_unknown(lower, diag, upper, j, c_prev, c_self, c_next, n)
            elif state[j] == SLACK:
                diag[j - 1] -= 1.0
            # the film fraction F_j: the Couette flux it carries and its squeeze storage F_j s_j
            if upwind_left:
                f_prev, f_self, f_next = 0.0, k[j] + s[j], -k[j]
            else:
                f_prev, f_self, f_next = k[jm], s[j] - k[jm], 0.0
            if state[j] == FRACTION:
                _add_unknown(lower, diag, upper, j, f_prev, f_self, f_next, n)
            elif state[j] == FULL or model == SWIFT_STIEBER:
                _add_known(rhs, j, jm, jp, f_prev, f_self, f_next)
        if not tridiagonal_solve(lower, diag, upper, rhs):
            return -1
        # the violation of each node's sign condition, relative to its scale (0: none), and of
        # F >= 0, which is not a condition of the complementarity but of the content: such a node
        # needs more liquid than reaches it and fills
        for j in range(1, n):
            z = rhs[j - 1]
            empty[j] = 0.0
            if state[j] == FULL:
                y[j] = y_cav + z
                film[j] = 1.0
                violation[j] = -z / x_scale
            elif state[j] == FRACTION:
                y[j] = y_cav
                film[j] = z
                violation[j] = z - 1.0
                empty[j] = -z
            else:
                y[j] = y_cav
                film[j] = 1.0 if model == SWIFT_STIEBER else 0.0
                violation[j] = -z / w_scale
        greedy = iteration > SAFE_PASSES
        if not greedy and np.max(violation) <= SWITCH_TOLERANCE:
            # F < 0 switches once the complementarity has settled: a neighbour still switching
            # (a full node drawing liquid at x < 0) also drives F below zero
            violation[:] = empty
        elif greedy:
            for j in range(1, n):
                violation[j] = max(violation[j], empty[j])
        # Newton switches every violating node; past SAFE_PASSES (a non-M-matrix JFO system can
        # make sets of nodes cycle) only the first one downstream of the feed, a least-index
        # pivoting rule in the order in which the Couette flux carries the content
        first = 0
        for i in range(1, n):
            j = i if upwind_left else n - i
            if violation[j] > SWITCH_TOLERANCE:
                first = j
                break
        changed = first > 0
        for j in range(1, n):
            if violation[j] > SWITCH_TOLERANCE and (not greedy or j == first):
                flips[j] += 1
                if state[j] != FULL:
                    state[j] = FULL
                else:
                    state[j] = FRACTION if model == JFO else SLACK
        if greedy and changed and state[first] == FULL and flips[first] > 2:
            # a node that violates in both states (more content than its gap as a cavity,
            # suction as full film) cannot settle alone: the film reforms upstream of it
            up = first - 1 if upwind_left else (first + 1) % n
            if up > 0:
                state[up] = FULL
        if not changed:
            for j in range(1, n):  # the accepted solution, with rounding-level violations clipped
                y[j] = max(y[j], y_cav)
                film[j] = min(max(film[j], 0.0), 1.0)
            return iteration
    return -1


@jit
def _coarsen(integrals):
    """Integrals over pairs of cells: the same exact scheme on the grid of the even nodes."""
    coarse = np.zeros(((integrals.shape[0] + 1) // 2, integrals.shape[1]))
    for j in range(integrals.shape[0]):
        coarse[j // 2] += integrals[j]
    return coarse


@jit
def _settle(integrals, u_a, u_b, model, y_cav, state, y, film, max_iterations):
    """:func:`_active_set`, falling back on a continuation in the squeeze if it does not settle.

    The JFO matrix is not an M-matrix where a cavity's squeeze storage outweighs
    its Couette transport (a gap closing under a cavity), and from a distant start
    the switching can cycle. The squeeze enters the cell integrals linearly (the
    Q columns), so the problem with squeeze t eps' is at hand for any t: the
    fallback follows t from 0 (rotation only, which settles) to 1, starting each
    step from the last solution and halving a step that does not settle.
    """
    start = state.copy()
    passes = _active_set(integrals, 0.5 * (u_a + u_b), model, y_cav, state, y, film, max_iterations)
    if passes >= 0 or model != JFO:
        return passes
    scaled = integrals.copy()
    n = integrals.shape[0]
    t, step, total = 0.0, 0.25, max_iterations
    accepted = start
    while t < 1.0:
        trial_t = min(t + step, 1.0)
        for c in (QH3, QH2, SQH3, OQH3):
            scaled[:, c] = trial_t * integrals[:, c]
        trial = accepted.copy()
        full_film(scaled, u_a, u_b, y)
        if t == 0.0 and trial_t == step:  # the first step starts from its own full film
            for j in range(1, n):
                trial[j] = SLACK if y[j] < y_cav else FULL
        passes = _active_set(scaled, 0.5 * (u_a + u_b), model, y_cav, trial, y, film, max_iterations)
        if passes >= 0:
            t, accepted, step = trial_t, trial, min(2.0 * step, 1.0)
            total += passes
        else:
            step *= 0.5
            if step < MIN_CONTINUATION_STEP:
                return -1
    state[:] = accepted
    return total


@jit
def _multilevel_active_set(integrals, u_a, u_b, model, y_cav, y, film, max_iterations):
    """The active-set iteration on a hierarchy of grids, each level started from the coarser one.

    A cavity found on a grid of N cells is started from the fine full-film set,
    whose boundary can be O(1) away; the active-set passes then move it by
    about one node each (O(N) passes). Because the cell relations are exact for
    any cells, summing pairs of cell integrals gives the same scheme on the even
    nodes; solving there first leaves a few nodes to move per level. Returns
    the total passes, or -1.
    """
    levels = [integrals]
    while levels[-1].shape[0] > COARSEST_LEVEL:
        levels.append(_coarsen(levels[-1]))
    state = np.zeros(0, dtype=np.int64)
    total = 0
    for level in range(len(levels) - 1, -1, -1):
        cells = levels[level]
        n = cells.shape[0]
        y_level = np.empty(n)
        full_film(cells, u_a, u_b, y_level)
        previous = state
        state = np.zeros(n, dtype=np.int64)
        for j in range(1, n):
            if previous.size == 0:
                cavity = y_level[j] < y_cav
            elif j % 2 == 0:
                cavity = previous[j // 2] != FULL
            else:  # between two coarse nodes: cavitated if both are
                cavity = previous[j // 2] != FULL and previous[(j // 2 + 1) % previous.size] != FULL
            if cavity:
                state[j] = SLACK
        film_level = np.ones(n)  # the feed node is full
        passes = _settle(cells, u_a, u_b, model, y_cav, state, y_level, film_level, max_iterations)
        if passes < 0:
            return -1
        total += passes
    y[:] = y_level
    film[:] = film_level
    return total


@jit(inline="always")
def _add_unknown(lower, diag, upper, j, c_prev, c_self, c_next, n):
    """Column of unknown j (row index j - 1) in rows j-1, j, j+1 of the system of nodes 1..N-1."""
    diag[j - 1] += c_self
    if j > 1:
        upper[j - 2] += c_prev
    if j < n - 1:
        lower[j - 1] += c_next


@jit(inline="always")
def _add_known(rhs, j, jm, jp, c_prev, c_self, c_next):
    """Move a known contribution of node j to the right-hand sides of its rows (node 0 has none)."""
    if j > 0:
        rhs[j - 1] -= c_self
    if jm > 0:
        rhs[jm - 1] -= c_prev
    if jp > 0:
        rhs[jp - 1] -= c_next


@jit
def cavitating_film(integrals, u_a, u_b, model, y_cav, max_iterations, y_out, film_out, r_out):
    """The film under a cavitation model; return oint phi' sin, oint phi' omega, the torque sum, passes.

    Parameters
    ----------
    integrals : ndarray, shape (N, N_INTEGRALS)
        From :func:`lubrication.reynolds_kernels.cell_integrals`.
    u_a, u_b : float
        Wall speeds in the frame of the line of centres (m/s).
    model : int
        NONE, HALF_SOMMERFELD, SWIFT_STIEBER or JFO.
    y_cav : float
        (p_cav - p_ref)/(12 mu a) <= 0.
    max_iterations : int
        Bound on the active-set passes.
    y_out, film_out, r_out : ndarray, shape (N,)
        Receive y = phi - phi_ref at the nodes (y_0 = 0), the film fraction F and the
        mass residual R of :func:`balance` (at node 0, the feed's supply).

    Returns
    -------
    i_sin, i_chi, i_torque : float
        As :func:`lubrication.reynolds_kernels.full_film`.
    passes : int
        Active-set passes (0 when the full film does not cavitate); -1 if not converged.
    """
    n = integrals.shape[0]
    half_u = 0.5 * (u_a + u_b)
    i_sin, i_chi, i_torque = full_film(integrals, u_a, u_b, y_out)
    film_out[:] = 1.0
    passes = 0
    if model != NONE and np.min(y_out) < y_cav:
        weight = np.ones(n)
        if model == HALF_SOMMERFELD:
            for j in range(n):
                jp = j + 1 if j < n - 1 else 0
                lo, hi = y_out[j] - y_cav, y_out[jp] - y_cav
                if lo < 0.0 and hi < 0.0:
                    weight[j] = 0.0
                elif lo < 0.0 or hi < 0.0:
                    # the crossing by linear interpolation: the kept parts telescope to p_cav exactly
                    weight[j] = max(lo, hi) / abs(hi - lo)
            i_sin, i_chi, i_torque = _film_integrals(integrals, half_u, u_a, u_b, y_out, weight, film_out)
            for j in range(n):
                if y_out[j] < y_cav:
                    y_out[j] = y_cav
                    film_out[j] = 0.0
        else:
            passes = _multilevel_active_set(integrals, u_a, u_b, model, y_cav, y_out, film_out, max_iterations)
            if passes < 0:
                return np.nan, np.nan, np.nan, passes
            for j in range(n):
                jp = j + 1 if j < n - 1 else 0
                if y_out[j] == y_cav and y_out[jp] == y_cav:
                    weight[j] = 0.0
            i_sin, i_chi, i_torque = _film_integrals(integrals, half_u, u_a, u_b, y_out,
                                                     weight, film_out)
    balance(integrals, half_u, y_out, film_out if model == JFO else np.ones(n), half_u >= 0.0, r_out)
    if model == SWIFT_STIEBER:  # the content is not modelled: F marks the cavitated nodes
        for j in range(1, n):
            if y_out[j] == y_cav:
                film_out[j] = 0.0
    return i_sin, i_chi, i_torque, passes


@jit
def cavitating_film_forces(kind, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, kappa_g, omk_g,
                           cpsi, spsi, vpsi, ppsi, wpsi, m, h_tab, q_tab, cos_c, sin_c,
                           model, p_cav, p_ref, p_out, film_out, r_out):
    """f_eps, f_chi (N) and T_a (N m) of a cavitating film over the length, and the active-set passes.

    The arguments up to ``sin_c`` are those of :func:`lubrication.reynolds_kernels.film_forces`.
    ``p_out`` (Pa, absolute), ``film_out`` and ``r_out`` (m^2/s per unit length,
    :func:`balance`) have shape (N,). If the active set does not settle, the forces are NaN and
    the passes negative: an exception raised here would be lost in a compiled caller that holds
    this function as a value (the integrator's right-hand side), while a NaN makes the
    integrator shorten its step, or stop saying that the forces were not finite. The Python
    face (:func:`lubrication.cavitation.cavitating_forces`) raises with the reason.
    """
    n = spsi.size // m
    u_a = a * w_a
    u_b = (b if kind == ECCENTRIC else a) * w_b
    integrals = np.zeros((n, N_INTEGRALS))  # cell_integrals adds to it
    cell_integrals(kind, a, b, kappa, omk, eps_dot, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, m,
                   h_tab, q_tab, integrals)
    scale_p = 12.0 * mu * a
    y = np.empty(n)
    y_cav = (p_cav - p_ref) / scale_p
    i_sin, i_chi, i_torque, passes = cavitating_film(integrals, u_a, u_b, model, y_cav, 2 * n + 16,
                                                     y, film_out, r_out)
    if passes < 0:
        return np.nan, np.nan, np.nan, passes
    for j in range(n):
        # a cavitated node holds p_cav exactly, not p_ref + (p_cav - p_ref) rounded
        p_out[j] = p_cav if (model != NONE and y[j] <= y_cav) else p_ref + scale_p * y[j]
    scale = scale_p * a * length
    f_x = scale * i_sin
    f_y = scale * i_chi
    return (cos_c * f_x - sin_c * f_y, sin_c * f_x + cos_c * f_y, mu * a * a * length * i_torque, passes)


@jit
def half_sommerfeld_weights(y, y_cav, weight):
    """The half-Sommerfeld truncation's share of each cell above the cavitation level.

    ``weight[j]`` receives 1 where both nodes of cell j are at or above ``y_cav``, 0
    where both are below, and otherwise the part of the cell above ``y_cav`` by linear
    interpolation between the nodes, so that the kept pressure rises end at p_cav exactly.
    """
    n = y.size
    for j in range(n):
        jp = j + 1 if j < n - 1 else 0
        lo, hi = y[j] - y_cav, y[jp] - y_cav
        if lo < 0.0 and hi < 0.0:
            weight[j] = 0.0
        elif lo < 0.0 or hi < 0.0:
            weight[j] = max(lo, hi) / abs(hi - lo)
        else:
            weight[j] = 1.0
