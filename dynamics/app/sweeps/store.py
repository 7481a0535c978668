"""The results of a sweep on disk: ``sweep.csv``, one row per point, appended as points finish; ``sweep.json``.

``sweep.csv`` has the axis keys, ``point`` (:func:`dynamics.app.sweeps.spec.point_key`)
and then :data:`NUMBERS`. Rows are appended as batches arrive and flushed to disk,
so a crash loses at most the batches in flight and leaves at worst a last line
cut short, which :func:`read_rows` ignores and :class:`Table` drops before
appending. A sweep started again in the same folder runs only the points whose
key the table lacks. ``sweep.json``, the manifest, holds the fingerprint of the
sweep (:meth:`dynamics.app.sweeps.spec.Sweep.fingerprint`): a folder is resumed
only by the same sweep.

A sweep with a ``contact.seed`` axis is an ensemble of surface realisations:
``ensemble.csv`` (:func:`write_ensemble`) has, for each point of the other axes,
the count, mean, standard deviation and standard error of every number of
:data:`dynamics.ensemble.UNSTEADINESS` over the seeds, rewritten whole at the end
of each run of the sweep.
"""

from __future__ import annotations

import csv
import io
import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from dynamics.app.sweeps.spec import Sweep, SweepError
from numerics.files import write_text

__all__ = ["CSV_NAME", "ENSEMBLE_NAME", "MANIFEST_NAME", "NUMBERS", "REALISATION", "TEXT", "Table", "check_manifest",
           "read_rows", "read_table", "to_pandas", "write_ensemble"]

CSV_NAME = "sweep.csv"
MANIFEST_NAME = "sweep.json"
ENSEMBLE_NAME = "ensemble.csv"
#: The axis whose values are realisations of the surfaces, not parameters.
REALISATION = "contact.seed"

# What each row records after the axis values and the point key, in this order.
NUMBERS = (
    "status",  # how the run ended: completed, stopped (an event), failed or interrupted
    "regime",  # one of dynamics.app.sweeps.point.REGIMES
    "t_end_tau",  # time reached, in tau
    "final_kappa",  # kappa at the end: near 1 when the inner cylinder has sunk to the wall
    "turns_of_phi_late",  # turns of the line of centres over the second half: >= 1 winds round
    "phi_reversals_late",  # swings of phi over the second half: >= 2 rocks
    "omega_b_tau_growth_late",  # change of Omega_b tau over the second half: > 0 accelerates
    "omega_b_tau_final",  # Omega_b tau at the end
    "omega_b_change_late",  # (max - min of Omega_b over the second half) / |Omega_b| at the end: <1% rolls steadily
    "phi_range_late",  # max - min of phi over the second half (rad): ~0 steady
    "stop_event",  # the event that stopped the run: runaway, gap_floor, reynolds, or empty
    # with a [contact] section, the unsteadiness over the second half (dynamics.ensemble.UNSTEADINESS)
    "mean_speed_late",  # distance rolled over time (m/s, or b/tau in a dimensionless scene)
    "speed_spread_late",  # standard deviation of the speed about that mean
    "phi_mean_late",  # mean angle of the line of centres (rad; pi at the lowest point)
    "phi_rms_late",  # its standard deviation: the rocking amplitude (rad)
    "locked_fraction_late",  # share of the time locked (hard contact)
    "switch_rate_late",  # contact switches per unit time
    "power_at_2pi_a",  # share of the speed's fluctuation at the inner surface's wavelength, against distance
    "power_at_2pi_b",  # and at the outer surface's
    "steps",  # accepted integrator steps
    "wall_time_s",  # time spent on this point, building the scene included
    "reason",  # why the point failed; empty otherwise
)


def _format(value: Any) -> Any:
    """Floats to 7 significant digits (the table stays small); axis values are written separately."""
    if isinstance(value, float):
        return f"{value:.7g}"
    return value


def read_rows(path: str | os.PathLike) -> list[dict[str, str]]:
    """The complete rows of a ``sweep.csv`` (a last line cut short by a crash is left out)."""
    path = Path(path)
    if not path.exists():
        return []
    text = path.read_text(encoding="utf-8")
    if not text.endswith("\n"):
        text = text[:text.rfind("\n") + 1]
    return list(csv.DictReader(text.splitlines()))


#: The columns of :data:`NUMBERS` that hold text.
TEXT = ("status", "regime", "stop_event", "reason", "point")


def _value(name: str, text: str):
    """A cell of sweep.csv as what it means: text for :data:`TEXT`, an int for ``steps``, else a number
    (an axis value given as a string with units, "2.4 deg", stays a string)."""
    if name in TEXT:
        return text
    if name == "steps":
        return int(text) if text else None
    try:
        return float(text) if text else None
    except ValueError:
        return text


def read_table(path: str | os.PathLike) -> list[dict[str, Any]]:
    """The complete rows of a ``sweep.csv`` with numbers as numbers (:func:`read_rows` keeps the text)."""
    return [{k: _value(k, v) for k, v in row.items()} for row in read_rows(path)]


def to_pandas(path: str | os.PathLike):
    """``sweep.csv`` as a pandas DataFrame, one row per point, numbers as numbers."""
    try:
        import pandas as pd
    except ImportError as err:
        raise ImportError("to_pandas needs pandas: pip install pandas") from err
    return pd.DataFrame(read_table(path))


class Table:
    """``sweep.csv`` open for appending rows, as a context manager.

    Parameters
    ----------
    path : Path
    keys : sequence of str
        The sweep's axis keys: the first columns, written as given (every digit);
        ``point`` and :data:`NUMBERS` follow.

    Raises
    ------
    SweepError
        If the file exists with other columns.
    """

    def __init__(self, path: Path, keys: Sequence[str]):
        self.keys = tuple(keys)
        self.columns = [*self.keys, "point", *NUMBERS]
        if path.exists() and path.stat().st_size:
            data = path.read_bytes()
            header = next(csv.reader([data.split(b"\n", 1)[0].decode()]))
            if header != self.columns:
                msg = (f"{path} has the columns {', '.join(header)}, not those of this sweep "
                       f"({', '.join(self.columns)}); write to another folder (-o DIR)")
                raise SweepError(msg)
            if not data.endswith(b"\n"):  # a line cut short by a crash
                with path.open("r+b") as fh:
                    fh.truncate(data.rfind(b"\n") + 1)
            self._file = path.open("a", encoding="utf-8", newline="")
        else:
            # the header is written whole before any row: a sweep killed at once leaves a table, never an empty file
            header = io.StringIO()
            csv.writer(header, lineterminator="\n").writerow(self.columns)
            write_text(path, header.getvalue())
            self._file = path.open("a", encoding="utf-8", newline="")
        self._writer = csv.DictWriter(self._file, self.columns, lineterminator="\n")

    def append(self, rows: Iterable[Mapping[str, Any]]) -> None:
        """Write ``rows`` and flush them to disk."""
        self._writer.writerows({k: v if k in self.keys else _format(v) for k, v in row.items()} for row in rows)
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self) -> None:
        self._file.close()

    def __enter__(self) -> Table:
        return self

    def __exit__(self, *exc) -> bool:
        self.close()
        return False


def check_manifest(path: Path, sweep: Sweep) -> dict:
    """The manifest of a folder's sweep ({} if none yet), refused if the folder holds a different sweep."""
    if not path.exists():
        return {}
    manifest = json.loads(path.read_text(encoding="utf-8"))
    if manifest.get("fingerprint") != sweep.fingerprint():
        msg = (f"{path.parent} holds the results of another sweep ({manifest.get('source')}, fingerprint "
               f"{manifest.get('fingerprint')}); write to another folder (-o DIR)")
        raise SweepError(msg)
    return manifest


def write_ensemble(path: Path, rows: Iterable[Mapping[str, str]], keys: Sequence[str]) -> None:
    """``ensemble.csv`` of a sweep with the axes ``keys`` (one of them :data:`REALISATION`): the statistics of
    :func:`dynamics.ensemble.ensemble_statistics` over the realisations of each point of the other axes, failed
    points left out (the count says how many remain)."""
    from dynamics.ensemble import ensemble_statistics

    by = [k for k in keys if k != REALISATION]
    stats = ensemble_statistics([r for r in rows if r["regime"] != "failed"], by)
    text = io.StringIO()
    if stats:
        writer = csv.DictWriter(text, list(stats[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows({k: _format(v) for k, v in row.items()} for row in stats)
    write_text(path, text.getvalue())
