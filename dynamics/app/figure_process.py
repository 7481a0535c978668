"""The child process that draws trajectory.png while a run computes.

Drawing the figure costs about 0.7 s, half of it importing matplotlib: longer
than a default run takes once its kernels are compiled. :class:`FigureProcess`
starts ``python -m dynamics.app.figures`` before the run; the child imports
matplotlib and builds and renders the panels that do not depend on the run
(``_frame`` there) meanwhile, then draws what it is sent.
This module imports neither numpy nor matplotlib, so that the child starts as
soon as the command line is read (0.08 s earlier than from the drawing module,
which imports numpy first).
"""

from __future__ import annotations

import pickle
import subprocess
import sys
from types import SimpleNamespace
from typing import Self

__all__ = ["FigureProcess"]

#: What the figure reads of a :class:`~dynamics.simulation.Trajectory`: all the child receives.
FIELDS = ("columns", "dimensionless", "equations", "forces", "status", "message", "groups", "tau")


class FigureProcess:
    """Draws the figure in a child process; use as a context manager around the run.

    :meth:`send` hands the child a trajectory as soon as the run ends, so that
    it draws while the caller writes its other outputs; :meth:`png` then returns
    :func:`dynamics.app.figures.figure_png` of it. Leaving the context without
    calling them stops the child, which receives only :data:`FIELDS` and so never
    imports the integrator.
    """

    def __enter__(self) -> Self:
        # its own process group (setsid): Ctrl-C at the terminal reaches only the parent, which stops the child
        self._child = subprocess.Popen([sys.executable, "-m", "dynamics.app.figures"], stdin=subprocess.PIPE,
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
        self._sent = None
        return self

    def send(self, trajectory) -> None:
        """Hand ``trajectory`` to the child, which starts drawing it.

        Written here rather than by a thread: the child reads it at once when its
        panels are ready, and a thread would wait for the interpreter's lock while
        the caller works (30 ms, measured). Were the panels not ready, the caller
        would wait for them, which it would do in :meth:`png` anyway.
        """
        view = SimpleNamespace(**{name: getattr(trajectory, name) for name in FIELDS})
        self._sent = trajectory
        try:
            self._child.stdin.write(pickle.dumps(view, protocol=pickle.HIGHEST_PROTOCOL))
            self._child.stdin.flush()
        except BrokenPipeError:  # the child has failed: png() reports why
            pass

    def png(self, trajectory) -> bytes:
        """The PNG of ``trajectory``, drawn by the child (sent now unless :meth:`send` sent it)."""
        if self._sent is None:
            self.send(trajectory)
        elif trajectory is not self._sent:
            msg = "png() asked for another trajectory than the one sent to the child"
            raise ValueError(msg)
        png, err = self._child.communicate()
        if self._child.returncode != 0:
            lines = err.decode(errors="replace").strip().splitlines() or [f"exit status {self._child.returncode}"]
            msg = f"drawing trajectory.png failed: {lines[-1]}"  # the exception, without the child's traceback
            raise RuntimeError(msg)
        return png

    def __exit__(self, *exc) -> None:
        if self._child.returncode is None:
            self._child.kill()
            self._child.communicate()
