"""The documentation site builds with warnings as errors, what it generates from the code is complete,
and its Python examples run as printed.

One build of ``docs/site`` serves the tests here: the README's command, run as a
reader runs it, so the pages, the API reference, the command-line and scene
references, and the gallery with every example executed. It runs in a mirror of
the repository under a temporary folder (symbolic links to the sources), so that
its outputs (the gallery's pages, the generated API pages, the HTML) never touch
the working tree. A page with a reference to a missing function is planted in the
mirror: the build must fail on it, and on nothing else.

The build runs in the default test run, which installs the docs extra; its cost is
given in docs/site/building.md. The code blocks fenced as ```python in the pages run
too, as the README's do; a block that needs a file of the reader's is a
``{code-block}`` instead.
"""

from __future__ import annotations

import argparse
import html
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "docs" / "site"
#: The README's build, from the repository's root (the mirror's here).
COMMAND = ["python", "-m", "sphinx", "-W", "--keep-going", "-b", "html", "docs/site", "docs/site/_build/html"]
OUT = Path("docs", "site", "_build", "html")
EXAMPLES = sorted(path.stem for path in (SITE / "examples").glob("plot_*.py"))
GENERATED = {"_build", "auto_examples", "sg_execution_times.rst", "__pycache__"}
PLANTED = """---
orphan: true
---
# A planted page

It refers to {py:func}`lubrication.registry.no_such_function`, which does not exist.
"""


def _mirror(target: Path) -> Path:
    """``target`` laid out like the repository: links to every source, real folders where the build writes."""
    for entry in ROOT.iterdir():
        if entry.name not in ("docs", ".git"):
            (target / entry.name).symlink_to(entry)
    docs = target / "docs"
    docs.mkdir()
    for entry in (ROOT / "docs").iterdir():
        if entry.name != "site":
            (docs / entry.name).symlink_to(entry)
    site = docs / "site"
    site.mkdir()
    for entry in SITE.iterdir():
        if entry.name in GENERATED or entry.name == "api":
            continue
        (site / entry.name).symlink_to(entry)
    (site / "api").mkdir()
    for entry in (SITE / "api").iterdir():
        if entry.name != "generated":
            (site / "api" / entry.name).symlink_to(entry)
    (site / "planted.md").write_text(PLANTED)
    return site


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """Build the mirrored site once: (return code, warning lines, HTML folder, standard error)."""
    for module in ("sphinx", "myst_parser", "numpydoc", "sphinx_gallery", "sphinx-mathjax-offline"):
        pytest.importorskip(module, reason="the docs extra: pip install '.[docs]'")
    root = tmp_path_factory.mktemp("repository")
    _mirror(root)
    # the reader's environment, without a selection of examples: every example runs
    env = {name: value for name, value in os.environ.items() if name != "SNAIL_DOCS_EXAMPLES"}
    env["MPLBACKEND"] = "Agg"
    done = subprocess.run([sys.executable, *COMMAND[1:]], cwd=root, check=False, capture_output=True, text=True,
                          env=env, timeout=1800)
    warnings = [line for line in done.stderr.splitlines() if "WARNING" in line or "ERROR" in line]
    return done.returncode, warnings, root / OUT, done.stderr


def test_the_tests_build_the_site_as_the_readme_says():
    for page in (ROOT / "README.md", SITE / "building.md"):
        assert " ".join(COMMAND) in page.read_text(), page.name


def _text(page: Path) -> str:
    return html.unescape(re.sub(r"<[^>]+>", "", page.read_text()))


#: What makes a browser load a file when it shows a page: scripts, stylesheets and icons, images, frames.
_LOADS = re.compile(r'<(?:script|img|iframe|source|video|audio|embed)\b[^>]*?\ssrc="([^"]+)"'
                    r'|<link\b[^>]*?\shref="([^"]+)"|<object\b[^>]*?\sdata="([^"]+)"', re.IGNORECASE)
_REMOTE = re.compile(r"^(//|[a-z][a-z0-9+.-]*:)", re.IGNORECASE)  # a host or a scheme: not a file of the site


def _pages(out: Path) -> list[Path]:
    return [page for page in out.rglob("*.html") if not {"_static", "_images", "_sources"} & set(page.parts)]


def _loads(page: Path) -> list[str]:
    return [next(url for url in match if url) for match in _LOADS.findall(page.read_text())]


def _local_file(out: Path, page: Path, url: str) -> Path | None:
    """The file of the built site that ``url`` on ``page`` names, or None if it names none."""
    target = html.unescape(url).split("#")[0].split("?")[0]
    path = (page.parent / target).resolve() if target else page.resolve()  # "#...": the page itself
    return path if path.is_file() and out.resolve() in path.parents else None


def test_a_broken_reference_fails_the_build(build):
    code, warnings, _, stderr = build
    # 1: the build ran to its end and failed on its warnings (2 would be an error that stopped it)
    assert code == 1, f"a reference to a missing function must fail a build with -W, exit {code}: {stderr[-3000:]}"
    assert any("no_such_function" in w and "reference target not found" in w for w in warnings), stderr[-3000:]


def test_nothing_else_warns(build):
    _, warnings, _, stderr = build
    others = [w for w in warnings if "no_such_function" not in w]
    assert not others, "\n".join(others) + "\n" + stderr[-3000:]


@pytest.mark.parametrize("page", ["index", "getting_started", "physics", "force_models", "equations_of_motion",
                                  "inertia", "contact", "cavitation", "corrections", "speed_accuracy", "sweeps",
                                  "cli", "scenes", "validation", "building", "citing", "api/index",
                                  "auto_examples/index"])
def test_the_page_is_built(build, page):
    _, _, out, _ = build
    assert (out / f"{page}.html").is_file()


def test_the_gallery_has_examples():
    assert len(EXAMPLES) >= 10


@pytest.mark.parametrize("example", EXAMPLES)
def test_the_example_ran_to_its_end_and_its_page_has_its_figures_and_output(build, example):
    _, _, out, stderr = build
    path = out / "auto_examples" / f"{example}.html"
    page, text = path.read_text(), _text(path)
    assert "Traceback" not in text, text[text.index("Traceback"):][:2000]
    images = re.findall(rf"sphx_glr_{example}_\d+\.png", page)
    assert images, "the example's figure is missing from its page"
    assert all((out / "_images" / name).is_file() for name in set(images))
    assert 'class="sphx-glr-script-out' in page, "the example's printed output is missing from its page"
    assert f"examples/{example}.py" not in stderr, stderr[-3000:]  # a failed example is named in the warnings


def test_no_page_loads_anything_from_a_network(build):
    _, _, out, _ = build
    pages = _pages(out)
    assert len(pages) > 50
    remote = [f"{page.relative_to(out)}: {url}" for page in pages for url in _loads(page)
              if _REMOTE.match(url) and not url.startswith("data:")]
    missing = [f"{page.relative_to(out)}: {url}" for page in pages for url in _loads(page)
               if not _REMOTE.match(url) and _local_file(out, page, url) is None]
    # a CDN named anywhere in a page, a script's configuration included
    cdn = [f"{page.relative_to(out)}: {host}" for page in pages
           for host in re.findall(r"(?:https?:)?//([\w.-]+)", page.read_text()) if "cdn" in host.lower()]
    assert not remote + missing + cdn


def test_the_math_renderer_is_served_with_the_site(build):
    """The equations render offline: each page with math loads MathJax from the site's own files."""
    _, _, out, _ = build
    with_math = [page for page in _pages(out) if 'class="math' in page.read_text()]
    assert len(with_math) >= 5
    renderers = set()
    for page in with_math:
        scripts = [url for url in _loads(page) if "mathjax" in url.lower() and ".js" in url]
        assert scripts, f"{page.relative_to(out)} has equations but loads no MathJax"
        renderers |= {_local_file(out, page, url) for url in scripts}
    assert None not in renderers, "a page loads a MathJax that is not among the built files"
    # MathJax 3 draws with its own web fonts, which it loads from beside its script
    assert all(any((script.parent / "output" / "chtml" / "fonts" / "woff-v2").glob("*.woff")) for script in renderers)


def _documented_actions(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [a for a in parser._actions
            if not isinstance(a, argparse._HelpAction | argparse._SubParsersAction)]


def test_the_command_line_reference_has_every_subcommand_and_option(build):
    from dynamics.app.cli import build_parser

    _, _, out, _ = build
    page = (out / "cli.html").read_text()
    text = " ".join(_text(out / "cli.html").split())
    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    assert set(commands) >= {"forces", "run", "sweep", "validate", "corrections"}
    missing = [f"usage of snail {name}" for name in commands if f"usage: snail {name}" not in text]
    for name, sub in commands.items():
        for action in _documented_actions(sub):
            # an entry of Sphinx's option directive for each flag, and the help text argparse prints
            anchors = [f'id="cmdoption-snail-{name}-{flag.lstrip("-")}"' for flag in action.option_strings]
            anchors = anchors or [f'id="cmdoption-snail-{name}-arg-{action.metavar or action.dest}"']
            missing += [f"snail {name}: {anchor}" for anchor in anchors if anchor not in page]
            words = " ".join((action.help or "").split())[:40]
            if words not in text:
                missing.append(f"snail {name} {action.dest}: help {words!r}")
    assert not missing


def test_the_scene_reference_has_every_key_with_its_range(build):
    from dynamics.scenes.schema import SECTIONS

    _, _, out, _ = build
    text = _text(out / "scenes.html")
    missing = [f"[{section}]" for section in SECTIONS if f"[{section}]" not in text]
    for section, keys in SECTIONS.items():
        block = text[text.index(f"[{section}]"):]
        missing += [f"{section}.{key}: {rule.allowed()}" for key, rule in keys.items()
                    if key not in block or rule.allowed() not in block]
    assert not missing


@pytest.mark.parametrize("module", ["lubrication.registry", "dynamics.simulation", "dynamics.scenes.schema",
                                    "numerics.engine", "dynamics.contact.reduced", "dynamics.app.run"])
def test_the_api_reference_documents_what_the_module_exports(build, module):
    import importlib

    _, _, out, _ = build
    page = (out / "api" / "generated" / f"{module}.html").read_text()
    exported = importlib.import_module(module).__all__
    # each name is either documented on the page (an anchor) or linked to where it is defined
    missing = [name for name in exported if f'id="{module}.{name}"' not in page and f">{name}<" not in page]
    assert not missing


def test_the_api_reference_lists_every_public_module():
    """Every module of the three packages whose name has no leading underscore has its page, and no page is
    of a module that is gone."""
    conf = (SITE / "conf.py").read_text()
    listed = set(re.findall(r'"((?:lubrication|dynamics|numerics)[\w.]*)"', conf[conf.index("snail_api_groups"):]))
    modules = set()
    for package in ("lubrication", "dynamics", "numerics"):
        for path in (ROOT / package).rglob("*.py"):
            parts = path.relative_to(ROOT).with_suffix("").parts
            parts = parts[:-1] if parts[-1] == "__init__" else parts
            if not any(part.startswith("_") for part in parts):
                modules.add(".".join(parts))
    assert sorted(modules - listed) == [] and sorted(listed - modules) == []


PAGES_WITH_CODE = ["index.md", "getting_started.md"]
BLOCKS = [(page, code) for page in PAGES_WITH_CODE
          for code in re.findall(r"```python\n(.*?)```", (SITE / page).read_text(), flags=re.DOTALL)]


def test_the_pages_have_python_examples():
    assert len(BLOCKS) >= 3


@pytest.mark.parametrize(("page", "code"), BLOCKS, ids=[f"{page}-{i}" for i, (page, _) in enumerate(BLOCKS)])
def test_a_python_example_of_the_pages_runs(page, code, capsys):
    exec(compile(code, page, "exec"), {})  # noqa: S102 - the pages are ours
    assert capsys.readouterr().out.strip()  # each example prints its result
