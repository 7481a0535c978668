"""What every ``snail`` subcommand shares: bad input as :class:`UsageError`, numbers, progress, compiling.

Exit status: 0 success, 1 a failed computation, 2 bad input (a message that names
the offending value, and no traceback); :mod:`dynamics.app.cli` maps them.
"""

from __future__ import annotations

import argparse
import math
import sys
from contextlib import contextmanager

__all__ = ["UsageError", "announce_compiling", "number", "progress_bar"]


class UsageError(ValueError):
    """Bad input from the command line; reported with exit status 2."""


def number(text: str) -> float:
    """A finite number (every numeric option is a length, a rate, a pressure or a tolerance)."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        msg = f"not a finite number: {text!r}"
        raise argparse.ArgumentTypeError(msg)
    return value


class _Progress:
    """A tqdm bar, refreshed at most once a second; called with the time reached."""

    def __init__(self, total: float, unit: str, desc: str):
        from tqdm.auto import tqdm

        self.bar = tqdm(total=total, desc=desc, unit=unit, mininterval=1.0, leave=False,
                        bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} " + unit + " [{elapsed}<{remaining}]")

    def __call__(self, t: float) -> None:
        self.bar.update(t - self.bar.n)

    def close(self) -> None:
        self.bar.close()


def progress_bar(total: float, unit: str, desc: str):
    """A bar of the time reached on a terminal, called with it; None when standard error is piped."""
    return _Progress(total, unit, desc) if sys.stderr.isatty() else None


@contextmanager
def announce_compiling(command: str):
    """Say on standard error, once, when numba starts compiling a kernel in the block, and time it.

    Yields a dict whose ``compile_s`` holds the seconds spent compiling (0 when every kernel came from
    numba's cache): a first run after an install or an edit compiles, later runs load.
    """
    from numerics.jit import compile_watch

    def first(_):
        print(f"snail {command}: compiling the kernels of this model (first run after an install or an edit "
              "only; a minute or two)", file=sys.stderr, flush=True)

    with compile_watch(on_first=first) as watch:
        yield watch
