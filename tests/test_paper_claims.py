"""The table of the paper's statements against this tool's measurements, built from synthetic checks."""

import math

import pytest

from validation.checks import Check, Finding, absolute, relative
from validation.reports.paper_claims import CLAIMS, Claim, claim_rows, claims_table


def _one(f):
    return f"value {f['x'].measured:g}"


TOY = Claim("toy", "the paper says 1", {"x": "toy: x*"}, _one, lambda f: (f["x"].measured == 1.0, "reason"),
            optional={"y": "toy: y*"})


def _example(pattern: str, passed: bool = True) -> Check:
    """A check whose name matches ``pattern``, measuring what its reference says, passed or not."""
    name = pattern.replace("*", "1")
    if "estimate" in name:  # a number the report states without a verdict
        return Finding(name, 1.0)
    value = 0.25 if "share of" in name else 1.0
    return Check(name, value if passed else value + 1.0, value, 0.1, "absolute")


def _full_set(passed: bool = True) -> list[Check]:
    """One made-up check per pattern of every claim, so that every row can be worded."""
    checks = []
    for claim in CLAIMS:
        for pattern in {**claim.checks, **claim.optional}.values():
            checks.append(_example(pattern, passed))
    return checks


def test_missing_required_check_is_not_run_in_quick_mode():
    rows = claim_rows([], quick=True, claims=[TOY])
    assert rows[0].status == "not run"
    assert rows[0].measured == "not run in --quick"
    assert rows[0].missing == ("toy: x*",)
    assert claim_rows([], quick=False, claims=[TOY])[0].measured == "not run"


def test_measured_column_comes_from_the_checks():
    rows = claim_rows([relative("toy: x, first", 1.0, 1.0, 0.1), relative("other", 7.0, 7.0, 0.1)], claims=[TOY])
    assert rows[0].measured == "value 1"
    assert rows[0].status == "agrees" and rows[0].verdict == "**agrees**: reason"
    differs = claim_rows([relative("toy: x", 2.0, 2.0, 0.1)], claims=[TOY])[0]
    assert differs.status == "differs" and differs.measured == "value 2"


def test_a_failed_check_flags_the_verdict_even_when_optional():
    bad = relative("toy: x", 1.0, 2.0, 0.1)  # 50% off, 10% allowed
    row = claim_rows([bad], claims=[TOY])[0]
    assert not bad.passed
    assert row.status == "failed" and "check failed" in row.verdict and "toy: x" in row.verdict
    optional_bad = absolute("toy: y", 5.0, 0.0, 1.0)
    row = claim_rows([relative("toy: x", 1.0, 1.0, 0.1), optional_bad], claims=[TOY])[0]
    assert row.status == "failed" and row.failed == ("toy: y",)


def test_every_claim_is_worded_from_synthetic_checks():
    """With one passing check per pattern, every row is measured; with every check failing, every row is flagged."""
    rows = claim_rows(_full_set())
    assert [r.item for r in rows] == [c.item for c in CLAIMS]
    assert all(r.status in ("agrees", "differs") for r in rows), [(r.item, r.missing) for r in rows]
    assert all(r.status == "failed" for r in claim_rows(_full_set(passed=False)))


def test_each_row_names_only_its_own_checks():
    """Taking away one row's required checks leaves that row, and only that row, not run."""
    full = _full_set()
    for k, claim in enumerate(CLAIMS):
        own = {_example(p).name for p in claim.checks.values()}
        rows = claim_rows([c for c in full if c.name not in own], quick=True)
        statuses = [r.status for r in rows]
        assert statuses[k] == "not run", claim.item
        assert statuses.count("not run") == 1, (claim.item, statuses)


def test_table_is_markdown_with_one_row_per_claim_and_escaped_pipes():
    pipe = Claim("toy", "a | b", {"x": "toy*"}, lambda f: "|x|", lambda f: (True, "ok"))
    text = claims_table([relative("toy", 1.0, 1.0, 0.1)], claims=[pipe])
    lines = text.splitlines()
    assert lines[0].startswith("| Item | What the paper states | What this tool measures | Verdict")
    assert len(lines) == 3
    assert lines[2] == "| toy | a \\| b | \\|x\\| | **agrees**: ok |"
    assert len(claims_table([]).splitlines()) == 2 + len(CLAIMS)


@pytest.mark.parametrize("value", [math.nan, math.inf])
def test_non_finite_measurement_is_flagged_not_crashing(value):
    row = claim_rows([relative("toy: x", value, 1.0, 0.1)], claims=[TOY])[0]
    assert row.status == "failed"


def test_the_measured_number_reaches_the_table():
    """Changing a measured value in the run changes the rendered cell: nothing is hard-coded."""
    full = _full_set()
    q = next(c for c in full if c.name.startswith("figure 2 (mu_=1): decay exponent"))
    changed = [Check(c.name, 0.987654, c.reference, c.tolerance, c.kind) if c is q else c for c in full]
    row = next(r for r in claim_rows(changed) if r.item == "Figure 2: decay exponent q")
    assert "0.9877" in row.measured
