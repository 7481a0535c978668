"""Sphinx configuration of the snail-cylinder documentation.

Build (offline, warnings are errors), from the repository root::

    python -m sphinx -W --keep-going -b html docs/site docs/site/_build/html

The gallery (``examples/``) runs at build time, every example by default: that is
the build the README gives and the tests run. ``SNAIL_DOCS_EXAMPLES`` chooses
which examples execute (the others are shown without their output):

* unset or ``all``: every example;
* ``none``: none (the quickest build of the pages);
* anything else: a regular expression on the example's path
  (``SNAIL_DOCS_EXAMPLES=forces_against``).

Examples that have run are not run again while their source is unchanged.
"""

from __future__ import annotations

import os
import re
import sys
from importlib.metadata import version as _version
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(ROOT))  # the project itself, as the examples and autodoc import it

os.environ.setdefault("MPLBACKEND", "Agg")  # no display while the examples run

project = "snail-cylinder"
author = "the snail-cylinder authors"
copyright = "the snail-cylinder authors"
release = _version("snail-cylinder")
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    # MathJax 3 served with the site, so that the equations render without a network
    # (sphinx.ext.mathjax alone loads it from a CDN): it copies MathJax into _static/mathjax/
    # and sets mathjax_path to it, over any mathjax_path given here.
    "sphinx-mathjax-offline",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "snail_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "examples"]  # the gallery's sources become auto_examples/
smartquotes = False  # primes are derivatives (eps', chi''), not quotation marks

# Every cross-reference must resolve: a broken one is a warning, and -W makes it an error.
nitpicky = True
# Docstring references to private or unresolvable names, until the docstrings are corrected
# (each one should name a documented object, or be an ``inline literal``).
nitpick_ignore = [
    ("py:class", "ContactParams"),  # dynamics.contact.steady.steady_speed: dynamics.contact.reduced.ContactParams
    ("py:func", "_tabulate"),  # lubrication.reynolds.film_setup: a private function
]
nitpick_ignore_regex = [
    # Other libraries' objects have no target offline (intersphinx would need the network).
    (r"py:.*", r"(numpy|np|scipy|matplotlib|numba|pint|dask|distributed|skfem|meshio|tqdm)\..*"),
]

# -- MyST ------------------------------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# -- autodoc and numpydoc --------------------------------------------------------------------------
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types, with units
autodoc_default_options = {"show-inheritance": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# -- sphinx-gallery --------------------------------------------------------------------------------
_SELECTION = os.environ.get("SNAIL_DOCS_EXAMPLES", "all").strip() or "all"
_PATTERNS = {
    "all": r"/plot_[^/]*\.py$",
    "none": r"^$",
}
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": _PATTERNS.get(_SELECTION, _SELECTION),
    "ignore_pattern": r"__init__\.py|/_[^/]*\.py$",
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("snail_docs.figure_scraper", "matplotlib"),  # the project's own figures first
    "remove_config_comments": True,
    "min_reported_time": 1,
    "download_all_examples": False,
    # An example that raises is a warning like any other defect: -W fails the build on it (exit
    # status 1) once --keep-going has listed every problem, the examples' tracebacks included.
    "only_warn_on_example_error": True,
    "abort_on_example_error": False,
    "capture_repr": (),  # the examples print what they show; no repr of a block's last value
    # No sg_execution_times pages: they load jQuery and DataTables from CDNs, and time the build's machine.
    "write_computation_times": False,
    "matplotlib_animations": False,
    "run_stale_examples": False,
}
try:
    re.compile(sphinx_gallery_conf["filename_pattern"])
except re.error as err:
    raise ValueError(f"SNAIL_DOCS_EXAMPLES must be all, none or a regular expression, got "
                     f"{_SELECTION!r}: {err}") from err

# -- HTML ------------------------------------------------------------------------------------------
html_theme = "alabaster"
html_title = f"snail-cylinder {release}"
html_static_path = ["_static"]
html_css_files = ["snail.css"]
html_theme_options = {
    "description": "Fluid forces in an eccentric annulus and the equations of motion of the snail cylinder",
    "fixed_sidebar": True,
    "page_width": "1180px",
    "sidebar_width": "250px",
    "show_relbars": True,
}
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}
html_show_sourcelink = False

# -- the API reference (pages written into api/generated/ by the snail_docs extension) -------------------
snail_api_groups = [
    ("Fluid forces for one instant", [
        "lubrication", "lubrication.registry", "lubrication.spec", "lubrication.kernels", "lubrication.geometry", "lubrication.closed_form",
        "lubrication.reynolds", "lubrication.cavitation", "lubrication.stokes_exact", "lubrication.stokes",
        "lubrication.reynolds2d", "lubrication.finite_length", "lubrication.stokes3d",
        "lubrication.navier_stokes", "lubrication.inertia", "lubrication.angular_momentum", "lubrication.film", "lubrication.film_transport", "numerics.files",
    ]),
    ("Compiled kernels of the force models", [
        "lubrication.reynolds_kernels", "lubrication.cavitation_kernels", "lubrication.reynolds2d_kernels",
        "lubrication.stokes_mesh", "lubrication.inertia_table", "lubrication.spin_table", "lubrication.tables", "lubrication.film_kernels", "numerics",
        "numerics.jit", "numerics.stamps",
    ]),
    ("Simulation", [
        "dynamics", "dynamics.simulation", "dynamics.trajectory", "dynamics.analysis", "dynamics.regime", "dynamics.initial", "dynamics.apparatus",
        "numerics.keys",
    ]),
    ("Equations of motion", [
        "dynamics.equations", "dynamics.equations.full", "dynamics.equations.reduced",
        "dynamics.equations.special", "dynamics.equations.limits",
        "dynamics.equations.film", "dynamics.equations.navier_stokes",
    ]),
    ("Unsteady Navier-Stokes flow in the gap", [
        "lubrication.unsteady", "lubrication.unsteady.mapping", "lubrication.unsteady.spectral",
        "lubrication.unsteady.operator", "lubrication.unsteady.system", "lubrication.unsteady.timestepping",
        "lubrication.unsteady.walls", "lubrication.unsteady.resolution", "lubrication.unsteady.solver",
        "lubrication.unsteady.prescribed", "lubrication.unsteady.energy", "lubrication.unsteady.snapshots",
    ]),
    ("Rough contact", [
        "dynamics.contact", "dynamics.contact.reduced", "dynamics.contact.full", "numerics.hybrid",
        "dynamics.contact.steady", "dynamics.contact.roughness", "dynamics.contact.rough",
        "dynamics.contact.rough_full", "dynamics.contact.laws", "dynamics.ensemble", "dynamics.tilt",
    ]),
    ("The integrator", [
        "numerics.integrate", "numerics.engine", "numerics.engine.ivp", "numerics.engine.driver",
        "numerics.engine.compiled", "numerics.engine.radau", "numerics.engine.roots", "numerics.engine.linalg",
        "numerics.engine.state", "numerics.engine.borrow", "numerics.packed",
    ]),
    ("Scenes", ["dynamics.scenes", "dynamics.scenes.schema", "dynamics.scenes.load", "numerics.units"]),
    ("The application: runs, files, sweeps, the command", [
        "dynamics.app", "dynamics.app.run", "dynamics.app.output", "dynamics.app.figures",
        "dynamics.app.figure_process",
        "dynamics.app.auto", "numerics.folder", "dynamics.app.cli", "dynamics.app.precompile", "dynamics.app.sweeps",
        "dynamics.app.sweeps.spec", "dynamics.app.sweeps.point", "dynamics.app.sweeps.compiled",
        "dynamics.app.sweeps.batch", "dynamics.app.sweeps.store", "dynamics.app.sweeps.run",
        "dynamics.app.sweeps.plot", "dynamics.app.command", "dynamics.app.commands", "dynamics.app.commands.forces", "dynamics.app.commands.run",
        "dynamics.app.commands.sweep", "dynamics.app.commands.fit", "dynamics.fit",
        "dynamics.app.flow_spec", "dynamics.app.flow_run", "dynamics.app.commands.flow",
    ]),
]
