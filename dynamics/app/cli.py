"""The ``snail`` command: the subcommands of the ``snail.commands`` entry-point group, and the exit status.

Exit status: 0 success, 1 a failed computation, 2 bad input (with a message that
names the offending value, and no traceback). Every subcommand is a module with a
``register(subparsers)`` named in the entry-point group (``pyproject.toml``), those
of ``dynamics`` (:mod:`dynamics.app.commands`) as those of ``validation``, so that
``dynamics`` never imports a package above it.
"""

from __future__ import annotations

import argparse
import gc
import logging
import re
import signal
import sys
from contextlib import contextmanager
from importlib.metadata import entry_points, version

from dynamics.app.command import UsageError
from numerics.folder import FolderError

__all__ = ["UsageError", "build_parser", "main"]

# A value that argparse would otherwise take for an option: -1e-6, -.5, -inf ...
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.IGNORECASE)

#: The order of the subcommands in ``snail --help``; any other registered command follows.
ORDER = ("forces", "run", "flow", "sweep", "fit", "validate", "corrections")


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        self.print_usage(sys.stderr)
        self.exit(2, f"{self.prog}: error: {message}\n")


def _join_negative_values(argv: list[str]) -> list[str]:
    """Turn ``--flag -1e-6`` into ``--flag=-1e-6``: argparse reads -1e-6 as an option."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        token = argv[i]
        if (token.startswith("--") and "=" not in token and i + 1 < len(argv)
                and _NEGATIVE_NUMBER.match(argv[i + 1])):
            out.append(f"{token}={argv[i + 1]}")
            i += 2
        else:
            out.append(token)
            i += 1
    return out


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="snail", description="The snail cylinder: fluid forces, trajectories, validation.")
    parser.add_argument("--version", action="version", version=f"snail {version('snail-cylinder')}")
    subparsers = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    found = {ep.name: ep for ep in entry_points(group="snail.commands")}
    for name in sorted(found, key=lambda n: (ORDER.index(n) if n in ORDER else len(ORDER), n)):
        found[name].load()(subparsers)
    return parser


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where Python runs, as Ctrl-C is: every command stops the way it stops on Ctrl-C."""


def _terminate(signum, _frame):
    raise Terminated


_terminate.interrupts_runs = True  # inside an integration the engine takes SIGTERM over (numerics.engine)


#: Loggers whose messages a command shows on standard error, and from which level: the project's warnings, and
#: the notice of a table built on first use (a minute of silence otherwise).
_SHOWN = {"numerics": logging.WARNING, "lubrication": logging.WARNING, "dynamics": logging.WARNING,
          "validation": logging.WARNING, "lubrication.finite_length": logging.INFO}


@contextmanager
def _messages(command: str):
    """The project's log messages on standard error as ``snail <command>: message`` while a command runs."""
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter(f"{command}: %(message)s"))
    loggers = {name: logging.getLogger(name) for name in _SHOWN}
    before = {name: (log.level, log.propagate) for name, log in loggers.items()}
    for name, log in loggers.items():
        log.setLevel(_SHOWN[name])
        if name.count(".") == 0:
            log.addHandler(handler)
    try:
        yield
    finally:
        for name, log in loggers.items():
            log.setLevel(before[name][0])
            if name.count(".") == 0:
                log.removeHandler(handler)


def main(argv: list[str] | None = None) -> int:
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return _main(argv)
    finally:
        signal.signal(signal.SIGTERM, previous)


def _main(argv: list[str] | None) -> int:
    argv = _join_negative_values(sys.argv[1:] if argv is None else list(argv))
    command = "snail"
    try:
        args = build_parser().parse_args(argv)
        command = f"snail {args.command}"
        with _messages(command):
            return args.run(args)
    except (UsageError, FolderError) as err:
        print(f"{command}: error: {err}", file=sys.stderr)
        return 2
    except Terminated:
        print(f"{command}: interrupted by SIGTERM", file=sys.stderr)
        return 128 + signal.SIGTERM
    except KeyboardInterrupt:
        print(f"{command}: interrupted", file=sys.stderr)
        return 130
    except Exception as err:  # a failed computation: say what failed, keep the exit status apart
        print(f"{command}: computation failed: {type(err).__name__}: {err}", file=sys.stderr)
        return 1


def console() -> int:
    """The ``snail`` command: :func:`main` on the command line's arguments, then a quick exit.

    Everything a command loads lives until the process ends, and Python's last
    collections at exit would walk it all: 0.2 s of a 2 s ``snail run`` with
    numba's and matplotlib's objects loaded. Frozen, they are left to the
    operating system.
    """
    status = main()
    gc.freeze()
    return status


if __name__ == "__main__":
    sys.exit(console())
