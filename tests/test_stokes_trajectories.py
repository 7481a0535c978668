"""The Stokes-against-lubrication trajectory group in its quick form."""

from validation import stokes_trajectories
from validation.checks import comparisons


def test_quick_group_passes(tmp_path):
    records, figures, text = stokes_trajectories.run(tmp_path, quick=True)
    checks = comparisons(records)
    failed = [c.name for c in checks if not c.passed]
    assert len(checks) == 3 and len(records) == 5  # and the two findings of the Reynolds passages
    assert not failed
    assert figures == []
    assert "| steel | 200 | 1 |" in text
