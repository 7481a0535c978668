"""The Stokes-against-lubrication trajectory group in its quick form."""

from validation import stokes_trajectories


def test_quick_group_passes(tmp_path):
    checks, figures, text = stokes_trajectories.run(tmp_path, quick=True)
    failed = [c.name for c in checks if not c.passed]
    assert len(checks) == 3
    assert not failed
    assert figures == []
    assert "| steel | 200 | 1 |" in text
