"""The unsteadiness of a run and its statistics over realisations of the surfaces (dynamics.ensemble).

The numbers of one run are checked on a record whose answers are known in closed form
(a steady speed with a ripple at the inner surface's wavelength, a rocking angle, phases
of known duration): the averages are time-weighted sums over row intervals, second order
in the rows' spacing: the speed of a row interval differs from the ripple's by
(k dt)^2 / 24 = 1e-5 with 16,001 rows over the second half, and an average over a
span that is not a whole number of rocking periods by at most 2 / (omega span) of
its amplitude (7e-4); the tolerances are set above these. The ensemble statistics are checked on values whose mean
and spread are known by hand, and on rough runs of the reduced model: two disjoint sets of
realisations must agree within three combined standard errors.
"""

from __future__ import annotations

import csv
import math
from types import SimpleNamespace

import numpy as np
import pytest

from dynamics.app.sweeps.point import run_point
from dynamics.app.sweeps.spec import parse_sweep
from dynamics.app.sweeps.store import REALISATION, write_ensemble
from dynamics.ensemble import UNSTEADINESS, ensemble_statistics, unsteadiness
from dynamics.trajectory import PHASE_CODES

A, B = 0.008, 0.01125  # m
V, RIPPLE, TILT, ROCK, OMEGA = 2e-3, 1e-5, 0.2, 0.05, 3.0  # m/s, m, rad, rad, rad/s


def _record(rows: int = 32001):
    """x_b = V t + RIPPLE sin(x / a) (a ripple of wavelength 2 pi a against distance), phi rocking about
    pi - TILT, locked for 30 % of the second half, four switches in it."""
    k = V / A  # rad/s: the ripple's angular frequency in time
    t_end = 2.0 * (2.0 * math.pi / k) * 40  # the second half holds 40 whole ripples
    t = np.linspace(0.0, t_end, rows)
    phase = np.where((t >= t_end / 2) & (t < t_end / 2 + 0.3 * t_end / 2), PHASE_CODES["locked"],
                     PHASE_CODES["sliding"]).astype(float)
    columns = {"t": t, "x_b": V * t + RIPPLE * np.sin(k * t), "phi": math.pi - TILT + ROCK * np.sin(OMEGA * t),
               "one_minus_kappa": np.full(rows, 1e-2), "omega_b": np.full(rows, V / B), "phase": phase}
    events = [{"name": name, "t": f * t_end} for name, f in
              (("touch", 0.1), ("stick", 0.6), ("slip", 0.7), ("lift", 0.8), ("touch", 0.9), ("gap_floor", 0.95))]
    return SimpleNamespace(columns=columns, events=events), t_end, k


def test_the_unsteadiness_of_a_known_record():
    record, t_end, k = _record()
    got = unsteadiness(record, A, B)
    span = t_end / 2
    assert got["mean_speed_late"] == pytest.approx(V, abs=1e-4 * RIPPLE * k)
    assert got["speed_spread_late"] == pytest.approx(RIPPLE * k / math.sqrt(2.0), rel=1e-4)
    assert got["phi_mean_late"] == pytest.approx(math.pi - TILT, abs=1e-3 * ROCK)
    assert got["phi_rms_late"] == pytest.approx(ROCK / math.sqrt(2.0), rel=1e-3)
    dt = t_end / (record.columns["t"].size - 1)
    assert got["locked_fraction_late"] == pytest.approx(0.3, abs=dt / span)  # the switch falls within a row
    assert got["switch_rate_late"] == pytest.approx(4 / span, rel=1e-12)
    assert got["power_at_2pi_a"] > 0.9 and got["power_at_2pi_b"] < 0.05  # the ripple is the inner surface's


def test_a_run_without_contact_or_rows_gives_nan_where_it_cannot_say():
    record, _, _ = _record(rows=9)
    del record.columns["phase"]
    got = unsteadiness(record, A, B)
    assert math.isnan(got["locked_fraction_late"]) and math.isnan(got["power_at_2pi_a"])
    assert got["mean_speed_late"] > 0
    assert set(got) == set(UNSTEADINESS)


def test_a_run_that_rolls_back_late_has_no_spectrum_and_is_not_a_failure():
    """Forward over the second half, backward over its last nine tenths (where the spectrum is read)."""
    t = np.linspace(0.0, 100.0, 2001)
    x_b = np.where(t < 55.0, 1e-3 * t, 0.055 - 1e-6 * (t - 55.0))
    record = SimpleNamespace(columns={"t": t, "x_b": x_b, "phi": np.full(t.size, math.pi),
                                      "one_minus_kappa": np.full(t.size, 1e-2), "omega_b": np.zeros(t.size)},
                             events=[])
    got = unsteadiness(record, A, B)
    assert got["mean_speed_late"] > 0 and math.isnan(got["power_at_2pi_a"])


def test_ensemble_statistics_of_values_known_by_hand():
    rows = [{"incline.alpha": "0.04", "contact.seed": str(s), "mean_speed_late": str(v)} for s, v in
            enumerate((1.0, 2.0, 3.0, 4.0))]
    rows += [{"incline.alpha": "0.08", "contact.seed": "0", "mean_speed_late": "5"},
             {"incline.alpha": "0.08", "contact.seed": "1", "mean_speed_late": ""},
             {"incline.alpha": "0.08", "contact.seed": "2", "mean_speed_late": "nan"}]
    first, second = ensemble_statistics(rows, ["incline.alpha"], ["mean_speed_late"])
    assert first["realisations"] == 4 and first["mean_speed_late_n"] == 4
    assert first["mean_speed_late_mean"] == 2.5
    assert first["mean_speed_late_sd"] == pytest.approx(math.sqrt(5.0 / 3.0), rel=1e-15)
    assert first["mean_speed_late_se"] == pytest.approx(math.sqrt(5.0 / 3.0) / 2.0, rel=1e-15)
    assert second["realisations"] == 3 and second["mean_speed_late_n"] == 1
    assert second["mean_speed_late_mean"] == 5.0 and math.isnan(second["mean_speed_late_se"])


def test_an_integer_seed_axis_is_integers():
    sweep = parse_sweep('[base]\napparatus = {preset = "steel"}\nfluid = {nu = "500 cSt"}\n'
                        'incline = {alpha = "2.4 deg"}\ncontact = {sigma = "124 um"}\nrun = {t_end = "1 s"}\n'
                        '[axes]\n'
                        '"contact.seed" = {start = 0, stop = 3, num = 4}\n')
    assert sweep.axes[0].values == (0, 1, 2, 3)


ROUGH = {"apparatus": {"preset": "steel"}, "fluid": {"nu": "500 cSt"}, "incline": {"alpha": "2.4 deg"},
         "initial": {"kappa": 0.9, "phi": 3.14159}, "model": {"equations": "reduced"},
         "contact": {"sigma": "124 um", "friction_angle": "5 deg", "roughness_amplitude": 0.3,
                     "roughness_correlation": "2 mm"},
         "run": {"t_end": "20 s", "max_gap_reynolds": "none"}}


def test_two_disjoint_ensembles_of_rough_runs_agree_within_their_standard_errors(tmp_path):
    """Realisations of the reduced rough model (steel, 500 cSt, 2.4 deg): the mean speed and the rocking
    amplitude of seeds 0-7 and of seeds 8-23 agree within three combined standard errors, and the
    standard error of the larger set is the smaller."""
    rows = [run_point(ROUGH, {REALISATION: seed}) for seed in range(24)]
    assert all(r["regime"] != "failed" for r in rows), [r["reason"] for r in rows]
    assert all(math.isfinite(r["mean_speed_late"]) for r in rows)
    small, large = (ensemble_statistics(part, [])[0] for part in (rows[:8], rows[8:]))
    for name in ("mean_speed_late", "phi_rms_late"):
        gap = abs(small[f"{name}_mean"] - large[f"{name}_mean"])
        assert gap < 3.0 * math.hypot(small[f"{name}_se"], large[f"{name}_se"]), name
        assert large[f"{name}_se"] < small[f"{name}_se"], name
        assert small[f"{name}_sd"] > 0, name  # the surfaces make the runs differ
    text = [{k: str(v) for k, v in r.items()} for r in rows]
    write_ensemble(tmp_path / "ensemble.csv", text, [REALISATION])
    (table,) = list(csv.DictReader((tmp_path / "ensemble.csv").open()))
    assert int(table["realisations"]) == 24 and int(table["mean_speed_late_n"]) == 24
