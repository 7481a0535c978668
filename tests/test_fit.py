"""Inferring the roughness from the unsteadiness (dynamics.fit): the ABC machinery against posteriors known in
closed form, the statistics against records whose answer is known, the files, and the command."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.fit import STATISTICS, Prior, abc_posterior, read_fit_scene, read_record, summary_statistics
from dynamics.scenes import SceneError

A, B = 0.008, 0.01125  # m


def _gaussian_table(n: int, noise: float, seed: int):
    """theta ~ U(0, 1); every statistic is theta plus independent N(0, noise^2) noise."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(0.0, 1.0, (n, 1))
    stats = theta + noise * rng.standard_normal((n, len(STATISTICS)))
    return theta, stats


def test_abc_recovers_the_posterior_of_a_gaussian_model():
    """With k statistics each theta + N(0, s^2), the posterior of theta given observed values y (flat prior, far
    from its bounds) is N(mean(y), s^2/k). Regression ABC on 200,000 draws keeping 2 % must find its median
    and its 5 and 95 % quantiles (mean -+ 1.645 s/sqrt(k)) within the Monte-Carlo error of 4,000 weighted draws
    and the kernel's smoothing: 0.1 s/sqrt(k) (measured 0.01-0.03)."""
    noise, k = 0.02, len(STATISTICS)
    theta, stats = _gaussian_table(200_000, noise, seed=1)
    observed = np.full(k, 0.5) + noise * np.random.default_rng(2).standard_normal(k)
    result = abc_posterior([Prior("contact.psi", 0.0, 1.0)], observed, theta, stats, accept=0.02)
    sd = noise / math.sqrt(k)
    centre = float(np.mean(observed))
    low, high = result.interval["contact.psi"]
    assert result.estimate["contact.psi"] == pytest.approx(centre, abs=0.1 * sd)
    assert low == pytest.approx(centre - 1.645 * sd, abs=0.15 * sd)
    assert high == pytest.approx(centre + 1.645 * sd, abs=0.15 * sd)


def test_abc_intervals_hold_their_stated_coverage_on_a_model_they_know():
    """Over 200 data sets of the same Gaussian model with thetas drawn from the prior, 90 % intervals must
    contain the truth in 90 % of them; the binomial standard error at n = 200 is 2.1 %, so 84-96 %."""
    theta, stats = _gaussian_table(50_000, 0.05, seed=3)
    rng = np.random.default_rng(4)
    hits = 0
    for truth in rng.uniform(0.2, 0.8, 200):
        observed = truth + 0.05 * rng.standard_normal(len(STATISTICS))
        low, high = abc_posterior([Prior("contact.psi", 0.0, 1.0)], observed, theta, stats,
                                  accept=0.05).interval["contact.psi"]
        hits += low <= truth <= high
    assert 0.84 <= hits / 200 <= 0.96


def test_adjusted_draws_stay_inside_the_priors_bounds():
    theta, stats = _gaussian_table(20_000, 0.05, seed=5)
    result = abc_posterior([Prior("contact.psi", 0.0, 1.0)], np.full(len(STATISTICS), 0.999), theta, stats)
    assert np.all((result.samples > 0.0) & (result.samples < 1.0))
    log_prior = Prior("contact.sigma", 1e-5, 1e-3, log=True)
    y = log_prior.to_free(np.array([1e-5 * 1.0001, 3e-4, 1e-3 * 0.9999]))
    np.testing.assert_allclose(log_prior.from_free(y), [1e-5 * 1.0001, 3e-4, 1e-3 * 0.9999], rtol=1e-9)


def _record(speed, t_end=60.0, n=6000):
    t = np.linspace(0.0, t_end, n)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (speed(t[1:]) + speed(t[:-1])) * np.diff(t))])
    return t, x


def test_the_statistics_see_a_steady_speed_as_steady():
    t, x = _record(lambda t: np.full_like(t, 0.01))
    s = summary_statistics(t, x, A, B)
    assert s[0] == pytest.approx(math.log(0.01), rel=1e-12) and s[1] < 1e-9


@pytest.mark.parametrize(("radius", "band", "other"), [(A, 2, 3), (B, 3, 2)])
def test_the_statistics_find_kicks_that_recur_once_a_turn(radius, band, other):
    """A speed modulated once per 2 pi r of distance rolled (v = v0 (1 + 0.3 sin(x/r)), which X_b' = v makes a
    function of t): its fluctuation's power lies at 2 pi r (the band holds nearly all of it, the other
    body's band nearly none) and it correlates with itself one turn later."""
    v0, r = 0.01, radius

    def speed(t):
        return v0 * (1.0 + 0.3 * np.sin(v0 * t / r))  # x ~ v0 t: the modulation recurs every 2 pi r rolled

    t, x = _record(speed, t_end=2000.0, n=40000)
    s = summary_statistics(t, x, A, B)
    assert s[band] > 0.8 and s[other] < 0.1
    assert s[band + 2] > 0.8


def test_a_fit_scene_names_its_unknowns_and_their_priors_in_si():
    raw, priors = read_fit_scene("""
[apparatus]
preset = "steel"
[contact]
sigma = "124 um"
friction_angle = "5 deg"
roughness_amplitude = 0.2
roughness_correlation = "5 mm"
[run]
t_end = 10.0
[fit]
"contact.roughness_amplitude" = {low = 0.05, high = 0.6}
"contact.roughness_correlation" = {low = "1 mm", high = "20 mm", log = true}
""")
    assert "fit" not in raw
    assert priors == [Prior("contact.roughness_amplitude", 0.05, 0.6), Prior("contact.roughness_correlation",
                                                                                 1e-3, 2e-2, log=True)]


@pytest.mark.parametrize(("fit", "words"), [
    ("", "no [fit] section"),
    ('[fit]\n"contact.seed" = {low = 0, high = 9}', "fit.contact.seed: not a numeric scene key"),
    ('[fit]\n"model.forces" = {low = 0, high = 9}', "not a numeric scene key"),
    ('[fit]\n"contact.psi" = {low = 0.5, high = 0.1}', "low must be below high"),
    ('[fit]\n"contact.sigma" = {low = "1 kg", high = "2 kg"}', "fit.contact.sigma.low"),
    ('[fit]\n"contact.psi" = 0.3', "must be a table"),
])
def test_a_fit_scene_is_refused_naming_the_key(fit, words):
    with pytest.raises(SceneError, match=words.replace("[", r"\[")):
        read_fit_scene('[apparatus]\npreset = "steel"\n[contact]\nsigma = "124 um"\n[run]\nt_end = 1.0\n' + fit)


def test_a_record_is_read_and_refused_naming_what_is_wrong():
    t, x = read_record("t,x_b\n" + "".join(f"{0.1 * i},{0.001 * i}\n" for i in range(20)))
    assert t.size == 20 and x[-1] == pytest.approx(0.019)
    with pytest.raises(ValueError, match="columns t and x_b"):
        read_record("time,x\n0,0\n")
    with pytest.raises(ValueError, match="t must increase"):
        read_record("t,x_b\n" + "".join(f"{0.1 * (i % 3)},{i}\n" for i in range(20)))


FIT_SCENE = """
[apparatus]
preset = "steel"
[fluid]
nu = "500 cSt"
[incline]
alpha = "2.4 deg"
[initial]
kappa = 0.9
phi = 3.14159
[model]
equations = "reduced"
[contact]
sigma = "124 um"
friction_angle = "5 deg"
roughness_amplitude = 0.3
roughness_correlation = "2 mm"
[run]
t_end = "5 s"
max_gap_reynolds = "none"
[fit]
"contact.roughness_amplitude" = {low = 0.05, high = 0.6}
"""


def test_snail_fit_writes_its_estimates_and_refuses_bad_input(tmp_path, capsys):
    """The command end to end on a short record of the reduced rough model (a handful of runs: the
    machinery, not the accuracy, which the coverage test measures)."""
    from dynamics.fit import simulate_record
    from dynamics.scenes import parse_scene

    raw, priors = read_fit_scene(FIT_SCENE)
    times = np.linspace(0.0, 5.0, 200)
    record = simulate_record(raw, priors, [0.3], 12345, times)
    (tmp_path / "data.csv").write_text("t,x_b\n" + "".join(f"{float(t)!r},{float(x)!r}\n" for t, x in zip(times, record)))
    (tmp_path / "scene.toml").write_text(FIT_SCENE)
    out = tmp_path / "out"
    code = main(["fit", str(tmp_path / "data.csv"), str(tmp_path / "scene.toml"), "-o", str(out), "--draws", "24",
                 "--accept", "1", "--json"])
    assert code == 0
    summary = json.loads(capsys.readouterr().out)
    low, high = summary["interval_90"]["contact.roughness_amplitude"]
    assert 0.05 <= low <= summary["estimate"]["contact.roughness_amplitude"] <= high <= 0.6
    assert sorted(p.name for p in out.iterdir()) == ["fit.json", "fit.png", "posterior.csv"]
    assert parse_scene(raw).contact.roughness_amplitude == 0.3
    code = main(["fit", str(tmp_path / "missing.csv"), str(tmp_path / "scene.toml"), "-o", str(tmp_path / "x")])
    assert code == 2 and not (tmp_path / "x").exists()


@pytest.mark.slow
def test_the_stated_intervals_hold_on_data_the_model_makes():
    """20 synthetic records of the reduced rough model (steel, 500 cSt, 60 s, camera at 25 Hz), each with its own
    surfaces, fitted for the roughness amplitude against one reference table: the 90 % intervals must contain the
    truth in 80-100 % of the records that roll (rough surfaces can hold the device, and such a record has nothing
    to fit); at least 16 of 20 roll."""
    from dynamics.fit import coverage

    raw, priors = read_fit_scene(FIT_SCENE.replace('t_end = "5 s"', 't_end = "60 s"'))
    times = np.arange(0.0, 60.0, 0.04)
    truths = np.random.default_rng(7).uniform(0.1, 0.55, (20, 1))
    contained, fits = coverage(raw, priors, truths, times, draws=600, accept=0.15)
    rolled = np.isfinite(contained[:, 0])
    assert rolled.sum() >= 16 and all((fit is None) == (not r) for fit, r in zip(fits, rolled))
    assert np.mean(contained[rolled, 0]) >= 0.8, contained.ravel()
