"""The snail cylinder's equations of motion, scenes, trajectories and the ``snail`` command."""
