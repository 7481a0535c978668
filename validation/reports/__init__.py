"""What the report shows of each study: its figures, its markdown and the group ``snail validate`` runs.

Each module here presents the study of the module of the same name in :mod:`validation`, which runs
the computations and makes the checks and imports nothing from here. ``run(outdir, quick)`` of a
module here is that study's group in :data:`validation.suite.GROUPS`: it calls the study's
computation, draws the figures (matplotlib is imported only by the drawing functions, so the quick
form, which draws none, never loads it) and words the paragraph. :mod:`.paper_claims` words the
report's first table from the checks of a whole run. A study with stored pages under ``docs/`` is
regenerated with ``python -m validation.reports.<study>``.
"""
