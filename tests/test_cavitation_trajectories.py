"""The cavitating-trajectory validation group in its quick form."""

from validation import cavitation_trajectories


def test_run_summary_counts_cavity_switches():
    trajectory = cavitation_trajectories.simulate(2.4, "jfo", 3.0, 1.0, n=64)
    fraction = cavitation_trajectories.cavitated_fraction(trajectory, 2.4, "jfo", 3.0, n=64)
    run = cavitation_trajectories.Run(2.4, "jfo", 3.0, trajectory, fraction)
    assert run.finite
    assert fraction[0] == 0.0  # from rest the film is full
    appear, _ = run.cavity_changes
    assert appear >= 1
