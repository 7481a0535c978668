"""The paper's statements next to what this tool measures: one markdown table for the report.

Each row of :data:`CLAIMS` quotes (in paraphrase, with section and equation
numbers of ``dissipative-descent.md``) what Balmforth, Bush, Vener & Young (2007)
state about one figure or result, and names the validation checks that measure
the same thing. :func:`claims_table` looks those checks up by name in the list a
run produced and fills the "measured" column from their measured values, so the
table is right for whatever the run measured:

* a required check that did not run gives "not run in --quick" (or "not run");
* a check that failed flags the verdict, whatever the row would otherwise say;
* otherwise the verdict is the row's: "agrees" or "differs", with the reason.

Check names are matched as shell-style patterns (:func:`fnmatch.fnmatchcase`;
a trailing ``*`` makes a prefix). The mapping row -> check names lives in
:data:`CLAIMS` and nowhere else: the functions that word a row see its checks
only through the row's keys.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from fnmatch import fnmatchcase

from ..checks import Check, Finding

__all__ = ["CLAIMS", "Claim", "Row", "claim_rows", "claims_table"]

HEADER = "| Item | What the paper states | What this tool measures | Verdict |"
NOT_RUN_QUICK = "not run in --quick"
NOT_RUN = "not run"


class Found:
    """The checks of one row, by the row's keys (optional keys may be missing)."""

    def __init__(self, matches: Mapping[str, list[Check]], quick: bool):
        self._matches = matches
        self.quick = quick

    def __getitem__(self, key: str) -> Check:
        return self._matches[key][0]

    def get(self, key: str) -> Check | None:
        found = self._matches.get(key)
        return found[0] if found else None

    def all(self, key: str) -> list[Check]:
        return list(self._matches.get(key, ()))

    @property
    def not_run(self) -> str:
        return NOT_RUN_QUICK if self.quick else NOT_RUN


@dataclass(frozen=True)
class Claim:
    """One row: the paper's statement, the checks that measure it, and how to word the result.

    ``checks`` and ``optional`` map a key to a pattern on check names; every
    required pattern must match at least one check for the row to be measured.
    ``measure(found)`` words the measured column; ``verdict(found)`` returns
    (agrees, reason) and is asked only when every check of the row passed.
    """

    item: str
    paper: str
    checks: Mapping[str, str]
    measure: Callable[[Found], str]
    verdict: Callable[[Found], tuple[bool, str]]
    optional: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class Row:
    """A rendered row; ``status`` is "agrees", "differs", "failed" or "not run"."""

    item: str
    paper: str
    measured: str
    verdict: str
    status: str
    failed: tuple[str, ...] = ()
    missing: tuple[str, ...] = ()


# -- wording helpers ------------------------------------------------------------------

def _g(x: float, digits: int = 4) -> str:
    return f"{x:.{digits}g}"


def _rel(c: Check) -> float:
    """|measured / reference - 1|, nan when the reference is zero."""
    return abs(c.measured / c.reference - 1.0) if c.reference else math.nan


def _share(x: float) -> str:
    """A relative difference: a percentage, or in scientific notation below 0.1%."""
    return f"{x:.1%}" if not x < 1e-3 else f"{x:.1e} (relative)"


def _worst(checks: Sequence[Check], of=lambda c: abs(c.measured)) -> float:
    return max((of(c) for c in checks), default=math.nan)


def _count(c: Check, word: str) -> str:
    """The number written before ``word`` in a check's name ("of 90 settled runs" -> "90")."""
    m = re.search(rf"(\d+) {word}", c.name)
    return m.group(1) if m else "?"


def _phase(code: float) -> str:
    from dynamics.trajectory import PHASE_CODES

    names = {v: k for k, v in PHASE_CODES.items()}
    return names.get(int(code), f"code {code:g}") if math.isfinite(code) else "nan"


# -- figure 2 -------------------------------------------------------------------------

def _rocking(f: Found) -> str:
    text = (f"Reduced model (2.11), Upsilon = mu_ = 1, s = 1/4: the run rocks down to the gap floor "
            f"1 - kappa = {_g(f['floor'].measured, 3)}; over the last 10 periods phi - phi* averages "
            f"{_g(f['centre'].measured, 2)} rad (phi* = pi + asin(s), sin(phi*) = -s); 1/zeta grows at "
            f"{_g(f['closing'].measured, 5)} per tau against (3.9)'s sqrt(1 - s^2) = {_g(f['closing'].reference, 5)}; "
            f"the rocking frequency is {_g(f['frequency'].measured, 5)} against (3.10)'s "
            f"{_g(f['frequency'].reference, 5)}.")
    extra = [f.get("frequency3"), f.get("closing3")]
    if all(extra):
        text += (f" mu_ = 3: frequency {_g(extra[0].measured, 5)} ({_g(extra[0].reference, 5)}), 1/zeta rate "
                 f"{_g(extra[1].measured, 5)} ({_g(extra[1].reference, 5)}).")
    else:
        text += f" mu_ = 3 frequency and rate: {f.not_run}."
    return text


def _rocking_verdict(f: Found) -> tuple[bool, str]:
    worst = max(_rel(f[k]) for k in ("closing", "frequency"))
    return True, (f"contact is approached only as t -> infinity, about sin(phi) = -s, at the closing rate and "
                  f"frequency of (3.9)-(3.10) to {_share(worst)}.")


def _exponent(f: Found) -> str:
    text = (f"Fitted decay exponent of the rocking envelope against zeta: {_g(f['q1'].measured, 4)} at mu_ = 1 "
            f"(q = {_g(f['q1'].reference, 4)})")
    q3 = f.get("q3")
    text += (f", {_g(q3.measured, 4)} at mu_ = 3 (q = {_g(q3.reference, 4)})." if q3
             else f"; mu_ = 3: {f.not_run}.")
    return text


def _exponent_verdict(f: Found) -> tuple[bool, str]:
    worst = _worst([c for c in (f.get("q1"), f.get("q3")) if c], _rel)
    return True, f"q of (3.10) to {_share(worst)}."


def _distance(f: Found) -> str:
    c = f["distance"]
    window = re.search(r"over \[([\d.]+), ([\d.]+)\]", c.name)
    text = (f"X_b gains {_g(c.measured, 4)} (units of b) per e-fold of t"
            f"{f' over [{window[1]}, {window[2]}] tau' if window else ''}, against 3 s/sqrt(1 - s^2) = "
            f"{_g(c.reference, 4)}: X_b = (3 s/sqrt(1 - s^2)) ln t + const (dynamics.equations.special.slow_approach).")
    q = f.get("q")
    if window and q:
        # X_b ~ t^(1-q) gains (1 - q) t^(1-q) per e-fold: it would grow by this factor across the window
        grow = (float(window[2]) / float(window[1])) ** (1.0 - q.reference) - 1.0
        text += f" The text's t^(1-q), q = {_g(q.reference, 4)}, would change that gain by {grow:+.0%} across it."
    return text


def _distance_verdict(f: Found) -> tuple[bool, str]:
    return False, ("the envelope t^-q belongs to the rocking, which has zero mean; the mean of Omega_b is "
                   "3 s zeta ~ 1/t, kept up by the shear of the closing film ((2.11b)-(2.11c) near contact), so "
                   "X_b grows as ln t for every mu_, and the finite stopping distance for q > 1 (aluminium, "
                   "section 4) does not follow.")


# -- figure 3 and the runaway ------------------------------------------------------------

def _runaway(f: Found) -> str:
    rates = ", ".join(f"{_g(c.measured, 4)}" for c in f.all("slopes"))
    return (f"Reduced model, Upsilon = mu_ = 1, s = 0.9: d/dt of (Omega_a, Omega_b, phi') = ({rates}) against "
            f"(3.11)'s s/((mu_ + 1/2) Upsilon) = {_g(f['slopes'].reference, 4)}, fitted as r t + c ln t + d (the "
            f"O(1/Omega) mean of kappa sin(phi) adds the ln t).")


def _runaway_verdict(f: Found) -> tuple[bool, str]:
    return True, f"the slope of (3.11) to {_share(_worst(f.all('slopes'), _rel))}."


def _acceleration(f: Found) -> str:
    a, paper, observed = f["model"].measured, f["paper"].value, f["observed"].value
    text = (f"Full model (2.1)-(2.7), aluminium apparatus at 5 degrees: {_g(a)} m/s^2 (quadratic fit to X_b), "
            f"{a / paper - 1:+.1%} against (3.11)'s {_g(paper)}, {a / observed - 1:+.1%} against the observed "
            f"2 g sin(alpha)/3 = {_g(observed)}, {a / f['rigid'].value - 1:+.1%} against the rigid body "
            f"{_g(f['rigid'].value)}; the model's own co-rotating asymptote (1 - f) a_0 = "
            f"{_g(f['model'].reference)} is met to {_rel(f['model']):.1e}.")
    steep = f.get("steep")
    if steep:
        text += f" At a steeper slope ({steep.name.split(':')[0]}) it is met to {_rel(steep):.1e}."
    return text


def _acceleration_verdict(f: Found) -> tuple[bool, str]:
    a, paper, observed = f["model"].measured, f["paper"].value, f["observed"].value
    if abs(a / paper - 1.0) <= 0.01:
        return True, "the model runs away at (3.11)'s acceleration to 1%."
    al = _aluminium()
    factor = 2.0 * (al.M + al.m_b + 0.5 * al.m_a) / al.M
    return False, (f"(3.11) takes the inner cylinder's moment of inertia about the contact point as m_a b^2/2 "
                   f"(it is m_a a^2/2, a/b = {al.a / al.b:.2f}) and leaves out the eccentric mass m_eff delta^2, "
                   "the fluid's own spin (which the full equations carry by default, and the Navier-Stokes runs "
                   "confirm: docs/stokes_limit.md) "
                   f"and the film's shear loss in each turn, so the model is {a / paper - 1:+.1%} off it. The "
                   f"observed law is {observed / a - 1:+.1%} from the model and {observed / paper - 1:+.1%} from "
                   f"(3.11), which the text calls a match (2(M + m_b + m_a/2)/M = {factor:.2f}, not 3).")


def _aluminium(alpha_deg: float = 5.0):
    """The paper's aluminium apparatus (Table 2) at ``alpha_deg``."""
    from dynamics.apparatus import preset

    return preset("aluminium", alpha=math.radians(alpha_deg))


def _rest_point(f: Found) -> str:
    from dynamics.equations.special import critical_slope

    al = _aluminium()
    return (f"Full model: a rest point at contact needs M b sin(alpha) < m'_a delta, i.e. s b/a < 1; for the "
            f"aluminium apparatus alpha < {math.degrees(critical_slope(al)):.2f} degrees. At 5 degrees "
            f"(s = {al.s:.2f}, s b/a = {al.s * al.b / al.a:.2f}) {f['full5'].measured:.0%} of "
            f"{_count(f['full5'], 'starts')} starts from rest run away in the full model, "
            f"{f['reduced5'].measured:.0%} in the reduced (2.11); at 4 degrees the full model runs away from "
            f"{f['full4'].measured:.0%}.")


def _rest_point_verdict(f: Found) -> tuple[bool, str]:
    if f["full5"].measured < 1.0:
        return True, "at 5 degrees some starts still rock in the full model, as s < 1 allows."
    al = _aluminium()
    rocks = 1.0 - f["reduced5"].measured
    return False, (f"s < 1 is the leading-order criterion (a = b); at the apparatus's delta/a = "
                   f"{al.delta / al.a:.2f} the torque balance at contact needs s b/a < 1, so at 5 degrees the full "
                   f"model has no rest point and every start runs away, as the aluminium cylinder did in figure 6"
                   + (f", while (2.11) still rocks from {rocks:.0%} of them." if rocks > 0 else "."))


# -- figures 7-10 -----------------------------------------------------------------------

def _figure7(f: Found) -> str:
    return (f"Touch at 1 - kappa = {_g(f['touch'].measured)} (1 - kappa* = {_g(f['touch'].reference)}); the run ends "
            f"{_phase(f['phase'].measured)}, phi within {_g(f['phi'].measured, 2)} of (5.6), Omega_a + Omega_b = "
            f"{_g(f['sum'].measured, 6)} against (5.7)'s {_g(f['sum'].reference, 6)}, both rates within "
            f"{_g(f['rates'].measured, 2)} (relative to 3 zeta* s) of (5.11) as corrected.")


def _figure7_verdict(f: Found) -> tuple[bool, str]:
    return True, ("steady sliding at the fixed point (5.6)-(5.9). (5.11) as printed carries an extra 1/2 in both "
                  "first terms and is not that fixed point (erratum 6); the run is measured against the "
                  "corrected form.")


def _figure8(f: Found) -> str:
    locked, jump, free = f["locked"], f["jump"], f["psi0"]
    return (f"psi = 0.5 ends {_phase(locked.measured)}, rates within {_g(f['locked_rates'].measured, 2)} of (5.10); "
            f"on locking Omega_a jumps by {_g(jump.measured, 5)} = Omega_b - Omega_a just before "
            f"({_g(jump.reference, 5)}). psi = 0 ends {_phase(free.measured)}, rates within "
            f"{_g(f['psi0_rates'].measured, 2)} of (5.11) as corrected.")


def _figure8_verdict(f: Found) -> tuple[bool, str]:
    return True, "the friction angle selects the final phase as (5.5) says, with the jump of Omega_a at locking."


def _figure9(f: Found) -> str:
    from ..contact_checks import FIGURE9_PSI, KAPPA_STAR, onset_slope

    rates = f["rates"]
    return (f"{_count(rates, 'runs')} simulated steady states on the fixed points (5.10)/(5.11 corrected) to "
            f"{_g(rates.measured, 2)} (relative to 3 zeta* s), {f['branch'].measured:g} on the other branch; "
            f"{_phase(f['below'].measured)} at 0.98 s_c, {_phase(f['above'].measured)} at 1.02 s_c, where the "
            f"exact locking test gives s_c = {onset_slope(FIGURE9_PSI, KAPPA_STAR):.4f} and (6.4) gives "
            f"{onset_slope(FIGURE9_PSI):.4f} (psi = {FIGURE9_PSI:g}, kappa* = {KAPPA_STAR:g}).")


def _figure9_verdict(f: Found) -> tuple[bool, str]:
    from ..contact_checks import FIGURE9_PSI, KAPPA_STAR, onset_slope

    off = onset_slope(FIGURE9_PSI) / onset_slope(FIGURE9_PSI, KAPPA_STAR) - 1.0
    return True, (f"locked below the onset, sliding above it, on (5.10)-(5.11) once erratum 6 is fixed; (6.4) is "
                  f"the kappa* -> 1 limit of the locking test (whose tan(phi) is tan(psi), erratum 7) and places "
                  f"the onset {off:+.2%} off at kappa* = {KAPPA_STAR:g}.")


def _figure10(f: Found) -> str:
    compact = f["compact"].measured
    return (f"{_count(f['speeds'], 'settled')} settled dimensional runs of the apparatus: b Omega_b equals (6.1)-(6.2) with the exact fixed point to "
            f"{_g(f['speeds'].measured, 2)}; V/V* is the same for every oil to {_g(f['spread'].measured, 2)}; "
            f"(6.1) with the compact (5.12) is off by up to {compact:.3g} zeta*^2 ({compact * 0.04:.1%} at "
            f"zeta* = 0.2); {f['branch'].measured:g} runs on the other branch.")


def _figure10_verdict(f: Found) -> tuple[bool, str]:
    from ..contact_checks import ZETAS

    return True, (f"scaling by V* collapses the oils and the lines (zeta*/2) sin(alpha) are (6.1)'s locked "
                  f"branch, to O(zeta*^2) ({f['compact'].measured * 0.04:.1%} at zeta* = 0.2). The tool draws "
                  f"the caption's zeta* = {', '.join(f'{z:g}' for z in ZETAS)}.")


# -- finite gap, cavitation -----------------------------------------------------------

def _corrections(f: Found) -> str:
    from ..corrections import APPARATUS, C_FORMS

    slopes = [c.measured for c in f.all("slope")]
    c0 = {name: (form(0.0), form(0.99)) for name, form in C_FORMS.items()}
    cs = ", ".join(f"{name} {lo:.3g}" + (f"..{hi:.3g}" if abs(hi - lo) > 1e-9 else "")
                   for name, (lo, hi) in c0.items())
    small = min(min(v) for v in c0.values()) * APPARATUS["delta_over_a"]
    big = max(max(v) for v in c0.values()) * APPARATUS["delta_over_a"]
    text = (f"Full Stokes / (2.5)-(2.7) = 1 + c delta/a: log|ratio - 1| against log(delta/a) has slope "
            f"{min(slopes):.3f}..{max(slopes):.3f}; the fitted c(kappa) is, to {_worst(f.all('c')):.1e}, c = {cs} "
            f"(kappa 0..0.99), so at the apparatus's delta/a = {APPARATUS['delta_over_a']:.2f} the first-order "
            f"correction alone is +{small:.0%} to +{big:.0%}.")
    limit = f.get("limit")
    if limit:
        text += f" The full model departs from (2.11) at slope {limit.measured:.3f} in delta/a."
    gap, speed = f.get("gap"), f.get("speed")
    if gap and speed:
        text += (f" Along the apparatus's trajectories Stokes forces leave the gap at least {gap.measured:.2f} times "
                 f"wider and the mean speed at most {speed.measured:.2f} times the lubrication run's.")
    else:
        text += f" Trajectories with Stokes forces: {f.not_run}."
    return text


def _corrections_verdict(f: Found) -> tuple[bool, str]:
    from ..corrections import APPARATUS

    return False, (f"the ordering is confirmed (every correction is first order in delta/a), but at delta/a = "
                   f"{APPARATUS['delta_over_a']:.2f} it is not small: the leading-order forces underestimate the "
                   f"resistance, so the sinking and the rolling of the actual apparatus are slower than (2.11) "
                   f"predicts.")


_CAVITY = re.compile(r"^(?P<model>.+?), (?P<drop>[^,]+) Pa: steady gap.*, (?P<slope>[^,]+) deg$")


def _cavitation(f: Found) -> str:
    steady = f.all("steady")
    parsed = [m for m in (_CAVITY.match(c.name) for c in steady) if m]
    models = sorted({m["model"] for m in parsed})
    drops = sorted({float(m["drop"]) for m in parsed})
    slopes = sorted({float(m["slope"]) for m in parsed})
    closing = _worst(f.all("closing"), lambda c: c.measured)
    return (f"{len(steady)} full-model runs of the steel apparatus with a rupturing film ({', '.join(models)}; "
            f"p_ref - p_cav = {', '.join(f'{d:g}' for d in drops)} Pa; {', '.join(f'{s:g}' for s in slopes)} "
            f"degrees): every gap settles, (1-kappa)(T)/(1-kappa)(T/2) - 1 at most {_worst(steady):.1e} in size, "
            f"and rolls at least {f['speed'].measured:.3g} times faster than the full film, whose gap keeps "
            f"closing (that ratio {closing:.3f}; t^-2 gives 1/4).")


def _cavitation_verdict(f: Found) -> tuple[bool, str]:
    return False, ("here every cavitation model, half-Sommerfeld truncation included, holds the inner cylinder "
                   "off the wall and gives steady rolling, under these conditions: the steel apparatus, 1-4 degrees, "
                   "p_ref held at the widest gap, the steady gap set by the chosen margin p_ref - p_cav (on 2.4 "
                   "degrees also with the film's content in the state and the end reservoirs' bubble setting the "
                   "reference, at a gap 0.28 times as wide); the text gives no details of the model it tried "
                   "(Vener 2006), so the cause of the difference cannot be traced. Its 20% is measured against "
                   "rough-contact rolling and cannot be compared with the ratio to the decelerating full film.")


def _speed_law(f: Found) -> str:
    return (f"Full model (2.1)-(2.4) with rough contact and exact Stokes forces, steel apparatus in 500 cSt oil "
            f"at 2.4 degrees, sigma = 50 microns: steady speed {f['stokes'].measured:.3f} times that of (6.1) "
            f"({f['stokes'].note}).")


def _speed_law_verdict(f: Found) -> tuple[bool, str]:
    return False, (f"at delta/a = 0.41 the finite-gap resistance slows the steady rolling to "
                   f"{f['stokes'].measured:.0%} of the leading-order law, so a roughness inferred from measured "
                   "speeds with (6.1)-(6.3) comes out too small.")


# -- the rows -----------------------------------------------------------------------------

CLAIMS: tuple[Claim, ...] = (
    Claim(
        "Figure 2: rocking to contact",
        "Sections 3.2-3.3, (3.6)-(3.10), figure 2 (Upsilon = mu_ = 1, s = 1/4): the inner cylinder sediments; "
        "contact takes infinite time, the gap closing as zeta = zeta(0)/(1 + t zeta(0) sqrt(1 - s^2)) (3.9), "
        "about the stable fixed point sin(phi) = -s, while the apparatus rocks at omega^2 = "
        "sqrt(1 - s^2)/(Upsilon (mu_ + 1/2)) (3.10).",
        {"floor": "figure 2 (mu_=1): 1 - kappa where it stopped*",
         "centre": "figure 2 (mu_=1): mean of phi - phi*",
         "closing": "figure 2 (mu_=1): growth rate of 1/zeta*",
         "frequency": "figure 2 (mu_=1): rocking frequency*"},
        _rocking, _rocking_verdict,
        optional={"frequency3": "figure 2 (mu_=3): rocking frequency*",
                  "closing3": "figure 2 (mu_=3): growth rate of 1/zeta*"}),
    Claim(
        "Figure 2: decay exponent q",
        "(3.9)-(3.10): the rocking decays as [1 + t zeta(0) sqrt(1 - s^2)]^-q, q = 3(1 + 4 mu_^2)/(2 (1 + 2 mu_)^2), "
        "from 5/6 (mu_ = 1) up to 3/2; Table 2 lists q = 0.98 (steel) and 1.14 (aluminium).",
        {"q1": "figure 2 (mu_=1): decay exponent*"},
        _exponent, _exponent_verdict,
        optional={"q3": "figure 2 (mu_=3): decay exponent*"}),
    Claim(
        "Figure 2: distance rolled X_b",
        "Section 3.2: once the fast rocking is filtered, Omega_b ~ t^-q, so X_b ~ t^(1-q); section 3.3: with "
        "mu_ = 1, X_b increases like t^(1/6). Section 4 infers that the aluminium device (q > 1) stops after a "
        "finite distance and the steel one (q < 1) keeps creeping.",
        {"distance": "figure 2 (mu_=1): distance rolled per e-fold*"},
        _distance, _distance_verdict,
        optional={"q": "figure 2 (mu_=1): decay exponent*"}),
    Claim(
        "Figure 3: runaway",
        "Section 3.3, figure 3 (Upsilon = mu_ = 1, s = 0.9): the solution locks into runaway rolling with "
        "Omega_a ~ Omega_b ~ phi' ~ s t/((mu_ + 1/2) Upsilon) (3.11).",
        {"slopes": "figure 3: d*/dt in the runaway*"},
        _runaway, _runaway_verdict),
    Claim(
        "Runaway acceleration",
        "(3.11) in dimensional form: acceleration M g sin(alpha)/(M + m_b + m_a/2). Section 4, figure 6: the "
        "aluminium cylinder at 5 degrees follows X = g t^2 sin(alpha)/3, nearly independent of viscosity, which "
        "the text says matches (3.11) because 2(M + m_b + m_a/2)/M is about 3.",
        {"paper": "aluminium at 5 deg: runaway acceleration estimate, paper's (3.11)*",
         "rigid": "aluminium at 5 deg: runaway acceleration estimate, rigid body*",
         "observed": "aluminium at 5 deg: runaway acceleration estimate, observed*",
         "model": "aluminium at 5 deg: runaway acceleration against the co-rotating*"},
        _acceleration, _acceleration_verdict,
        optional={"steep": "aluminium at * deg (s = *): runaway acceleration against the co-rotating*"}),
    Claim(
        "Rest-point criterion",
        "Section 3.2, (3.5): at contact the device is a pushed pendulum that can rock about sin(phi) = -s only "
        "for s < 1; section 3.3: the sedimenting, rocking solution disappears for s >= 1, and below that the "
        "initial condition selects rocking or runaway.",
        {"full5": "aluminium at 5 deg, full model: share of * starts from rest that run away*",
         "reduced5": "aluminium at 5 deg, reduced model: share of * starts from rest that run away*",
         "full4": "aluminium at 4 deg, full model: share of * starts from rest that run away*"},
        _rest_point, _rest_point_verdict),
    Claim(
        "Figure 7: sliding contact",
        "Section 5, figure 7 (Upsilon = mu_ = 1, s = 1/4, kappa* = 0.98, psi = 0.05): after the surfaces touch, "
        "the solution settles into steady rolling with the cylinders in sliding contact, at the fixed point "
        "(5.6)-(5.9) with the rates (5.11).",
        {"touch": "figure 7: 1 - kappa of the unlimited solution at the touch*",
         "phase": "figure 7: phase at the end*",
         "phi": "figure 7: phi at the end vs (5.6)*",
         "sum": "figure 7: Omega_a + Omega_b at the end vs (5.7)*",
         "rates": "figure 7: rates at the end vs corrected (5.11)*"},
        _figure7, _figure7_verdict),
    Claim(
        "Figure 8: locking",
        "Section 5, figure 8 (as figure 7, psi = 0.5, 0.05, 0): with psi = 0.5 friction locks the cylinders "
        "(Omega_a = Omega_b, (5.10)) and Omega_a jumps discontinuously at the moment of contact (an impulse); "
        "smaller psi leaves them sliding.",
        {"locked": "figure 8, psi = 0.5: phase at the end*",
         "locked_rates": "figure 8, psi = 0.5: rates at the end*",
         "jump": "figure 8, psi = 0.5: jump of Omega_a on locking*",
         "psi0": "figure 8, psi = 0: phase at the end*",
         "psi0_rates": "figure 8, psi = 0: rates at the end*"},
        _figure8, _figure8_verdict),
    Claim(
        "Figure 9: steady rates and onset of sliding",
        "Section 5, figure 9 (psi = 0.15): steady rates locked (5.10) or sliding (5.11), compact form (5.12) for "
        "zeta* << 1; section 6.2: sliding sets in suddenly at tan(psi) = s/(2 sqrt(1 - s^2)) (6.4). The locking "
        "test below (5.9) is printed with tan(phi).",
        {"rates": "figure 9: steady rates of * runs*",
         "branch": "figure 9: runs settled on the other branch*",
         "below": "figure 9: phase at s = 0.98 s_c*",
         "above": "figure 9: phase at s = 1.02 s_c*"},
        _figure9, _figure9_verdict),
    Claim(
        "Figure 10: theory lines",
        "Section 6.1: V = V* sin(alpha) zeta* Max(1/2, 1 - sqrt(1 - s^2) tan(psi)/s) (6.1), V* = b M delta g/"
        "(4 nu m''_a) (6.2), reducing to (V* zeta*/2) sin(alpha) on small slopes; figure 10(b) draws "
        "V/V* = (zeta*/2) sin(alpha) for zeta* = 0.1 and 0.2 (caption; the text says 0.2 and 0.4) and infers "
        "zeta* ~ 0.2, sigma ~ 50 microns (6.3).",
        {"speeds": "figure 10: speeds b Omega_b of * settled runs vs (6.1)*",
         "spread": "figure 10: spread of V/V* across the oils*",
         "compact": "figure 10: *(6.1) with the compact (5.12)*",
         "branch": "figure 10: settled runs on the other branch*"},
        _figure10, _figure10_verdict),
    Claim(
        "delta/a corrections",
        "Sections 2.1-2.2: the forces (2.5)-(2.7) are lubrication theory for delta = b - a << a and the reduced "
        "model (2.11) is leading order in delta/a (with sin(alpha) ~ delta/a); Table 2's apparatus has "
        "delta/a = 0.325/0.8 = 0.41. No correction is estimated; the text points to Finn & Cox (2001) for "
        "general gaps.",
        {"slope": "Stokes: slope of log*ratio - 1* against log(delta/a), *",
         "c": "Stokes: fitted c(kappa) against the derived coefficient, *"},
        _corrections, _corrections_verdict,
        optional={"limit": "full against reduced: log-log slope*",
                  "gap": "both rock: smallest (1-kappa) at the end, Stokes / lubrication*",
                  "speed": "both rock to 1-kappa=1e-3: largest mean speed ratio Stokes / lubrication*"}),
    Claim(
        "Speed law (6.1) at the apparatus' gap",
        "Section 6: the steady speed V = V* sin(alpha) zeta* Max(1/2, ...) (6.1)-(6.2), leading order in "
        "delta/a, is applied to the steel apparatus (delta/a = 0.41), and the minimum gap sigma ~ 50 microns "
        "(6.3) and the sandpaper roughness of Table 3 are inferred from measured speeds with it.",
        {"stokes": "full contact, steel apparatus: speed with Stokes forces over (6.1)*"},
        _speed_law, _speed_law_verdict),
    Claim(
        "Cavitation",
        "Section 7: simple models that truncate the pressure where it falls too low (the journal-bearing device) "
        "did not give enough lift to counter gravity and allow steady rolling (Vener 2006); bubbles drawn into "
        "the gap of the 500 cS oil raised the speed by less than about 20% (sections 6.1, 7). Rough contact is "
        "favoured, though neither argument is called conclusive.",
        {"steady": "*: steady gap, (1-kappa)(T)/(1-kappa)(T/2) - 1, * deg",
         "closing": "full film: gap still closing*",
         "speed": "smallest speed ratio to the full film*"},
        _cavitation, _cavitation_verdict),
)


# -- the table -----------------------------------------------------------------------

def _cell(text: str) -> str:
    return " ".join(text.replace("|", "\\|").split())


def claim_rows(checks: Sequence[Check | Finding], quick: bool = False, claims: Sequence[Claim] = CLAIMS) -> list[Row]:
    """One :class:`Row` per claim, measured from ``checks`` (the run's, in any order)."""
    rows = []
    for claim in claims:
        patterns = {**claim.optional, **claim.checks}
        matches = {key: [c for c in checks if fnmatchcase(c.name, pattern)] for key, pattern in patterns.items()}
        found = Found({k: v for k, v in matches.items() if v}, quick)
        missing = tuple(claim.checks[k] for k in claim.checks if not matches[k])
        if missing:
            rows.append(Row(claim.item, claim.paper, found.not_run, "not measured", "not run", missing=missing))
            continue
        failed = tuple(c.name for cs in matches.values() for c in cs if isinstance(c, Check) and not c.passed)
        measured = claim.measure(found)
        if failed:
            verdict = f"**check failed**, not established: {'; '.join(dict.fromkeys(failed))}"
            rows.append(Row(claim.item, claim.paper, measured, verdict, "failed", failed=failed))
            continue
        agrees, reason = claim.verdict(found)
        status = "agrees" if agrees else "differs"
        rows.append(Row(claim.item, claim.paper, measured, f"**{status}**: {reason}", status))
    return rows


def claims_table(checks: Sequence[Check | Finding], quick: bool = False, claims: Sequence[Claim] = CLAIMS) -> str:
    """The markdown table: item, what the paper states, what this tool measures, verdict."""
    lines = [HEADER, "|---|---|---|---|"]
    lines += [f"| {_cell(r.item)} | {_cell(r.paper)} | {_cell(r.measured)} | {_cell(r.verdict)} |"
              for r in claim_rows(checks, quick, claims)]
    return "\n".join(lines)
