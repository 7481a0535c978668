"""The ``snail`` subcommands, each a module with a ``register(subparsers)`` named in the ``snail.commands``
entry-point group of ``pyproject.toml``, the one way a subcommand joins the command (those of ``validation``
too, so that ``dynamics`` never imports a package above it).

    forces.py    snail forces: one instant, any registered force model
    run.py       snail run: a scene to a trajectory and its files
    flow.py      snail flow: unsteady Navier-Stokes flow for prescribed wall motions
    sweep.py     snail sweep: a parameter sweep on dask
"""
