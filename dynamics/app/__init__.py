"""The application layer: a scene in, files out, and the ``snail`` command.

    run.py      a scene in, a trajectory out (the modelling choices the scene asks for)
    auto.py     the automatic choice of equations and forces from the stored study
    regime.py   which motion a trajectory settled into
    output.py   trajectory.csv, summary.json, trajectory.png, written as one set
    cli.py      the ``snail`` command
    sweeps/     parameter sweeps on dask
"""
