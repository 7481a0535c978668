"""Checks of every model against closed forms, limits and the paper; ``snail validate`` writes the report."""
