"""The delta/a correction study: a quick run writes its files (its checks: tests/test_validation_groups.py)."""

import csv
import json
from argparse import ArgumentParser

import numpy as np
import pytest

from lubrication.geometry import RESISTANCE_NAMES as RATIO_NAMES
from validation import cli, corrections


def test_quick_run_writes_csv_json_and_figure(quick_group):
    outdir, checks, figures, text = quick_group("corrections")
    assert figures == ["corrections.png"]
    assert (outdir / "corrections.png").stat().st_size > 10_000
    rows = list(csv.DictReader((outdir / "corrections.csv").open()))
    assert {r["model"] for r in rows} == {"stokes", "reynolds-eccentric"}
    assert set(RATIO_NAMES) <= set(rows[0])
    summary = json.loads((outdir / "corrections.json").read_text())
    assert len(summary["checks"]) == len(checks)
    apparatus = summary["apparatus"]
    assert apparatus["delta_over_a"] == pytest.approx(0.40625)
    # the headline: (2.5) underestimates the squeeze resistance by 67-77 per cent there
    squeeze = apparatus["ratio"]["stokes"]["f_eps_per_eps_dot"]
    assert 1.6 < squeeze["min"] < squeeze["max"] < 1.8
    c = summary["thin_gap_coefficient"]["stokes"]
    np.testing.assert_allclose(c["f_eps_per_eps_dot"], 1.5, atol=2e-3)
    assert "delta/a = 0.4062" in text


def test_thin_gap_coefficient_recovers_a_known_expansion():
    deltas = corrections.THIN
    d = np.array(deltas)[:, None, None]
    c_true = np.arange(10.0).reshape(5, 2)
    ratios = 1.0 + c_true * d + 0.7 * d**2 - 2.0 * d**3
    np.testing.assert_allclose(corrections.thin_gap_coefficient(deltas, ratios), c_true, atol=1e-10)
    np.testing.assert_allclose(corrections.log_slope(deltas, 1.0 + 0.3 * d), 1.0, rtol=1e-12)


def test_subcommand_registers(tmp_path):
    parser = ArgumentParser()
    cli.register_corrections(parser.add_subparsers())
    args = parser.parse_args(["corrections", "-o", str(tmp_path), "--quick"])
    assert args.run is cli._corrections and args.output == str(tmp_path) and args.quick


def test_the_study_runs_without_the_finite_element_extra(monkeypatch):
    """The exact solution needs no scikit-fem; only the finite-element comparison rows are left out."""
    monkeypatch.setattr("importlib.util.find_spec", lambda name: None)
    assert corrections.fe_errors(corrections.QUICK_FE_CASES) == []
