"""The application layer: a scene in, files out, and the ``snail`` command.

    run.py             a scene in, a trajectory out (the modelling choices the scene asks for)
    auto.py            the automatic choice of equations and forces from the stored study
    output.py          trajectory.csv, summary.json, trajectory.png, written as one set
    folder.py          the output folder: checked and locked before a run, written as one set
    figures.py         the trajectory figure, drawn without pyplot
    figure_process.py  the child process that draws it while the run computes
    cli.py             the ``snail`` command
    precompile.py      the kernels of a first run, compiled into the wheel
    sweeps/            parameter sweeps on dask
"""
