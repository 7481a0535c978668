"""The random-roughness speed table (:mod:`validation.rough_speeds`) in markdown."""

from __future__ import annotations

__all__ = ["speed_table_markdown"]


def speed_table_markdown(uniform: float, rows) -> str:
    """The table of :func:`speed_table` in markdown."""
    lines = [f"uniform kappa* steady Omega_b (6.1): {uniform:.5g} / tau", "",
             "| amplitude | <Omega_b> | spread (seeds) | / uniform | Omega_b fluctuation | switches/tau | seeds |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {r.amplitude:g} | {r.mean:.5g} | {r.spread:.2g} | {r.ratio:.4f} | {r.fluctuation:.3g} | "
              f"{r.switch_rate:.3g} | {r.seeds} |" for r in rows]
    return "\n".join(lines)
