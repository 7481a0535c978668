"""Pages of the documentation generated from the code, so that nothing is stated twice.

* ``snail-cli``: the reference of a ``snail`` subcommand, from the parser the
  command itself builds (:func:`dynamics.app.cli.build_parser`), as Sphinx
  ``program``/``option`` entries that ``:option:`` can refer to.
* ``snail-scene-reference``: every section and key of a scene, from the schema
  (:data:`dynamics.scenes.schema.SECTIONS`): allowed values (``Key.allowed()``),
  unit, default (from the dataclasses) and help.
* ``snail-api-index`` and the API pages: one page per module of
  ``snail_api_groups`` (conf.py), written into ``api/generated/`` when the
  build starts, documenting what the module's ``__all__`` exports; a name a
  module re-exports is documented once, where it is defined, and linked from
  the other.
* :func:`plain_text_docstring`: docstrings state formulas as plain text; ``|x|``,
  ``mu_`` and indented formula blocks are made safe for reST before numpydoc reads them.
* :func:`register_aliases`: a short reference in a docstring (``:class:`Resistance```)
  resolves wherever the module imports the name, as Python resolves it.
* :func:`figure_scraper`: the gallery's images of matplotlib figures built
  without pyplot (as the project's own figures are); :func:`rerun_unexecuted_examples`
  runs again an example whose page was last built without running it.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import inspect
import os
import re
import weakref
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective

# -- helpers -------------------------------------------------------------------------------------------

_RST_SPECIAL = re.compile(r"([\\*`|_\[\]])")


def rst_escape(text: str) -> str:
    """``text`` as literal reST inline text: no emphasis, no references, no substitutions."""
    return _RST_SPECIAL.sub(r"\\\1", text)


def _literal(text: str) -> str:
    """``text`` as an inline literal, whatever backquotes it holds."""
    return f":code:`{rst_escape(text)}`" if "`" in text else f"``{text}``"


def _module_file(name: str) -> str | None:
    module = importlib.import_module(name)
    return getattr(module, "__file__", None)


class _Generated(SphinxDirective):
    """A directive whose reST is produced by :meth:`lines` and parsed in place."""

    def lines(self) -> list[str]:
        raise NotImplementedError

    def depends_on(self, *modules: str) -> None:
        """Re-read the page when the source of one of ``modules`` changes."""
        for name in modules:
            path = _module_file(name)
            if path:
                self.env.note_dependency(path)

    def run(self) -> list[nodes.Node]:
        content = StringList()
        for line in self.lines():
            content.append(line, f"<{self.name}>")
        node = nodes.container()
        self.state.nested_parse(content, self.content_offset, node, match_titles=True)
        return node.children


# -- docstrings written as plain text ---------------------------------------------------------------------

# The project's docstrings state formulas as plain text (``|W_a|``, ``mu_``, indented formula blocks):
# read as reST, ``|x|`` is a substitution, ``mu_`` a hyperlink reference and an indented block a
# block quote whose inner indentation is an error. Before numpydoc parses a docstring these become
# escaped characters and literal blocks, so the formulas show as written.

_STRUCTURED = {"parameters", "other parameters", "returns", "yields", "receives", "raises", "warns", "warnings",
               "attributes", "methods", "see also"}
_PROTECTED = re.compile(r"(``.+?``|:[\w:+.-]+:`[^`]*`|`[^`]+`_{0,2}|https?://\S+)")
_TRAILING_UNDERSCORE = re.compile(r"(?<=\w)_(?=$|[\s.,;:!?)\]}'\"/])")
_LIST_ITEM = re.compile(r"^(\s*)([*+-]|\d+[.)]|\(\w+\)|#\.)\s+")


def _escape_text(line: str) -> str:
    parts = _PROTECTED.split(line)
    for i in range(0, len(parts), 2):
        parts[i] = _TRAILING_UNDERSCORE.sub(r"\\_", parts[i].replace("|", r"\|"))
    return "".join(parts)


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def _content_indent(line: str) -> int:
    """Where the text of ``line`` starts: after the marker of a list item."""
    match = _LIST_ITEM.match(line)
    return match.end() if match else _indent(line)


def _opens_block(line: str) -> bool:
    """Whether an indented block after ``line`` is already meant as reST (a literal, a directive)."""
    text = line.strip()
    return text.endswith("::") or text.startswith(".. ")


def _is_underline(line: str) -> bool:
    text = line.strip()
    return len(text) >= 3 and set(text) <= {"-", "=", "~"}


def _is_prose(chunk: list[str]) -> bool:
    """An indented chunk of sentences rather than formulas: one indentation, no equations, ends a sentence."""
    indents = {_indent(line) for line in chunk}
    return len(indents) == 1 and not any("=" in line for line in chunk) and chunk[-1].rstrip().endswith((".", ".)"))


def _literal_block(chunk: list[str]) -> list[str]:
    """``chunk`` as a literal block, its layout kept, at its own indentation (so it stays in its list or quote)."""
    margin = " " * min(_indent(line) for line in chunk)
    return [margin + "::", ""] + ["    " + line for line in chunk]


def _chunks(lines: list[str]) -> list[list[str]]:
    """Runs of non-blank lines; a section title (a line and its underline) is a run of its own."""
    chunks, current = [], []
    for line in lines:
        if line.strip():
            current.append(line)
            if len(current) >= 2 and _is_underline(line) and not _is_underline(current[-2]):
                if len(current) > 2:
                    chunks.append(current[:-2])
                chunks.append(current[-2:])
                current = []
        elif current:
            chunks.append(current)
            current = []
    if current:
        chunks.append(current)
    return chunks


def plain_text_docstring(lines: list[str]) -> list[str]:
    """``lines`` of a numpydoc docstring with plain-text formulas made safe for reST (see above)."""
    out: list[str] = []
    section = ""
    base = 0  # where the text of the last paragraph starts
    literal_after = None  # indentation of a line ending in "::" (or a directive): deeper chunks are verbatim
    for chunk in _chunks(lines):
        if out:
            out.append("")
        first = _indent(chunk[0])
        if literal_after is not None and first > literal_after:
            out += chunk
            continue
        literal_after = None
        for i, line in enumerate(chunk[:-1]):
            if _is_underline(chunk[i + 1]):
                section = line.strip().lower()
        if section in _STRUCTURED or chunk[0].lstrip().startswith((".. ", ":", ">>>")):
            out += [line if _is_underline(line) else _escape_text(line) for line in chunk]
        elif first > base and not _LIST_ITEM.match(chunk[0]) and not _is_prose(chunk):
            out += _literal_block(chunk)
            continue
        else:
            # a paragraph of two lines or more that goes on more deeply indented: a formula continuing it
            split = len(chunk)
            if len(chunk) > 2 and _indent(chunk[1]) == first and not _LIST_ITEM.match(chunk[0]):
                split = next((k for k in range(2, len(chunk)) if _indent(chunk[k]) > first), len(chunk))
            out += [_escape_text(line) for line in chunk[:split]]
            if split < len(chunk):
                out += [""] + _literal_block(chunk[split:])
            base = _content_indent(chunk[0])
        if _opens_block(chunk[-1]):
            literal_after = _indent(chunk[-1])
    trailing = len(lines) - len("\n".join(lines).rstrip().split("\n")) if "".join(lines).strip() else 0
    return out + [""] * trailing


def _process_docstring(app, what, name, obj, options, lines) -> None:
    lines[:] = plain_text_docstring(lines)


# -- the command line -------------------------------------------------------------------------------------

def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _invocation(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    formatter = parser._get_formatter()
    return formatter._format_action_invocation(action)


def _action_lines(parser: argparse.ArgumentParser, action: argparse.Action) -> list[str]:
    help_text = (action.help or "") % {"default": action.default, "prog": parser.prog}
    extra = []
    if action.required and action.option_strings:
        extra.append("Required.")
    shown_default = action.default not in (None, False, [], argparse.SUPPRESS) and action.option_strings
    if shown_default and "default" not in help_text:
        extra.append(f"Default: {_literal(str(action.default))}.")
    body = rst_escape(help_text.strip())
    if extra:
        body = (body + ("" if not body or body.endswith((".", ")")) else ".")) + " " + " ".join(extra)
    return [f".. option:: {_invocation(parser, action)}", "", f"   {body.strip() or '(no help)'}", ""]


#: Width of the generated usage lines; argparse would otherwise take the width of the terminal building the docs.
USAGE_COLUMNS = "88"


def cli_lines(parser: argparse.ArgumentParser, program: str) -> list[str]:
    """reST for one parser: its description, usage, subcommands and options."""
    lines = [f".. program:: {program}", ""]
    if parser.description:
        lines += [rst_escape(parser.description), ""]
    columns = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = USAGE_COLUMNS
    try:
        usage = parser.format_usage().strip()
    finally:
        if columns is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = columns
    lines += [".. code-block:: text", ""] + [f"   {line}" for line in usage.splitlines()] + [""]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            lines += ["Subcommands:", ""]
            for choice in action._choices_actions:
                lines += [f"``{choice.dest}``", f"   {rst_escape(choice.help or '')}", ""]
        if isinstance(action, argparse._HelpAction | argparse._SubParsersAction):
            continue
        lines += _action_lines(parser, action)
    return lines


class CliDirective(_Generated):
    """``.. snail-cli:: run``: the reference of ``snail run``; no argument: the ``snail`` command itself."""

    optional_arguments = 1

    def lines(self) -> list[str]:
        from dynamics.app import cli

        self.depends_on("dynamics.app.cli", "dynamics.app.commands.forces", "dynamics.app.commands.run", "dynamics.app.commands.sweep", "validation.cli", "validation.corrections")
        parser = cli.build_parser()
        if not self.arguments:
            return cli_lines(parser, "snail")
        name = self.arguments[0]
        commands = _subparsers(parser)
        if name not in commands:
            msg = f"snail has no subcommand {name!r}; it has {', '.join(commands)}"
            raise self.error(msg)
        return cli_lines(commands[name], f"snail {name}")


# -- the scene schema ---------------------------------------------------------------------------------------

def _section_classes() -> dict[str, type]:
    """The dataclass behind each scene section."""
    from dynamics.apparatus import Apparatus
    from dynamics.scenes import schema

    classes = {"apparatus": Apparatus, "fluid": Apparatus, "incline": Apparatus, "groups": schema.Groups,
               "initial": schema.Initial, "model": schema.Model, "contact": schema.Contact,
               "cavitation": schema.Cavitation, "navier_stokes": schema.NavierStokes,
               "run": schema.Run}
    missing = set(schema.SECTIONS) - set(classes)
    if missing:
        msg = f"the scene reference does not know the section(s) {sorted(missing)}: add their dataclass"
        raise RuntimeError(msg)
    return classes


NO_DEFAULT = "\u2014"  # an em dash


def _default(rule, cls: type, section: str, key: str) -> str:
    """The default of ``section.key`` as a scene would write it, or a dash when it has none."""
    from dynamics.scenes.schema import field_of

    field = cls.__dataclass_fields__.get(field_of(section, key))
    if field is None or field.default is dataclasses.MISSING:
        return NO_DEFAULT
    value = field.default
    if value is None:
        return _literal(repr(rule.none)) if rule.none else NO_DEFAULT
    if isinstance(value, str):
        return _literal(repr(value))
    if isinstance(value, bool) or rule.integer:
        return _literal(str(value))
    shown = f"{value / rule.scale:g}"
    return _literal(shown + (f" {rule.unit}" if rule.unit and rule.scale != 1.0 else ""))


def _unit(rule) -> str:
    """How a value is written: its SI unit (or an angle's), and what a dimensionless scene takes."""
    if rule.choices:
        return "string"
    if rule.integer:
        return "integer"
    if rule.scale != 1.0:
        return f"rad, or a string such as {_literal(repr(rule.example))}"
    parts = []
    if rule.unit:
        parts.append(rst_escape(rule.unit))
    else:
        parts.append("number")
    if rule.dimension != "[]" and rule.example:
        parts.append(f"or a string such as {_literal(repr(rule.example))}")
    if rule.reduced_unit:
        parts.append(f"({rst_escape(rule.reduced_unit)} in a dimensionless scene)")
    return " ".join(parts)


def _alternatives() -> dict[tuple[str, str], str]:
    from dynamics.scenes.schema import ALTERNATIVES

    other = {}
    for section, first, second in ALTERNATIVES:
        other[section, first] = second
        other[section, second] = first
    return other


def _summary(cls: type) -> str:
    doc = inspect.getdoc(cls) or ""
    return doc.split("\n\n")[0].replace("\n", " ")


def scene_lines() -> list[str]:
    """reST for every section of :data:`dynamics.scenes.schema.SECTIONS`."""
    from dynamics.scenes.schema import SECTIONS

    classes = _section_classes()
    other = _alternatives()
    lines = []
    for section, keys in SECTIONS.items():
        title = f"[{section}]"
        lines += [f".. _scene-{section}:", "", title, "~" * len(title), ""]
        cls = classes[section]
        target = f":class:`~{cls.__module__}.{cls.__name__}`"
        if cls.__name__ == "Apparatus":
            lines += [f"Fields of {target} (SI units).", ""]
        else:
            lines += [f"{rst_escape(_summary(cls))} Fields of {target}.", ""]
        lines += [".. list-table::", "   :header-rows: 1", "   :widths: 16 24 22 12 36", "",
                  "   * - key", "     - allowed", "     - unit", "     - default", "     - meaning"]
        for key, rule in keys.items():
            meaning = rst_escape(rule.help)
            if (section, key) in other:
                meaning += f" (give this or {_literal(other[section, key])}, not both)"
            lines += [f"   * - {_literal(key)}", f"     - {rst_escape(rule.allowed())}", f"     - {_unit(rule)}",
                      f"     - {_default(rule, cls, section, key)}", f"     - {meaning}"]
        lines.append("")
    return lines


class SceneReferenceDirective(_Generated):
    """``.. snail-scene-reference::``: a table per scene section, from the schema."""

    def lines(self) -> list[str]:
        self.depends_on("dynamics.scenes.schema", "numerics.keys", "dynamics.apparatus", "dynamics.initial",
                        "dynamics.equations.limits")
        return scene_lines()


def force_model_lines() -> list[str]:
    """reST of the force-model registry (:mod:`lubrication.registry`): every model, its options, the compositions."""
    from lubrication import registry

    lines = [".. list-table::", "   :header-rows: 1", "   :widths: 14 46 40", "",
             "   * - model", "     - what it computes", "     - its own options"]
    for name in registry.names():
        spec = registry.get(name)
        options = "; ".join(f"{_literal(k)}: {rst_escape(key.help)}, {rst_escape(key.allowed())}"
                            for k, key in spec.options.items()) or "none"
        where = " In trajectories: " + _literal(spec.in_trajectories) + "." if spec.in_trajectories else ""
        needs = f" Needs the {_literal(spec.extra)} extra." if spec.extra else ""
        lines += [f"   * - {_literal(name)}", f"     - {rst_escape(spec.summary)}.{where}{needs}", f"     - {options}"]
    lines += ["", "The compositions, options any model may take where its rule allows:", "",
              ".. list-table::", "   :header-rows: 1", "   :widths: 20 80", "", "   * - option", "     - meaning"]
    for key_name, key in registry.option_keys(compositions_only=True).items():
        lines += [f"   * - {_literal(key_name)}", f"     - {rst_escape(key.help)}, {rst_escape(key.allowed())}"]
    return [*lines, ""]


class ForceModelReferenceDirective(_Generated):
    """``.. snail-force-models::``: the registered force models and the compositions, from the registry."""

    def lines(self) -> list[str]:
        self.depends_on("lubrication.registry", "lubrication.spec", "lubrication.closed_form", "lubrication.film",
                        "lubrication.stokes_exact", "lubrication.stokes", "numerics.keys")
        return force_model_lines()


# -- the API reference -------------------------------------------------------------------------------------

_ASSIGNED = r"^(?:\w+\s*,\s*)*{name}\s*(?:,\s*\w+\s*)*(:[^=\n]*)?="


def _exported(module, name: str):
    """``module.name``; a package's lazily exported function whose submodule has the same name is the function."""
    obj = getattr(module, name)
    if inspect.ismodule(obj) and hasattr(obj, name):
        obj = getattr(obj, name)
    return obj


def _is_code(obj) -> bool:
    """A class or a function (jitted ones included): something with a defining module of its own."""
    return inspect.isclass(obj) or (callable(obj) and isinstance(getattr(obj, "__module__", None), str))


def _assignment_line(module, name: str) -> int | None:
    """The line where ``module`` assigns ``name`` at top level, if it does."""
    try:
        source = inspect.getsource(module)
    except (OSError, TypeError):
        return None
    match = re.search(_ASSIGNED.format(name=re.escape(name)), source, flags=re.MULTILINE)
    return None if match is None else source.count("\n", 0, match.start()) + 1


def _defined_in(module, name: str) -> bool:
    """Whether ``name`` is defined by ``module`` itself rather than imported into it."""
    obj = _exported(module, name)
    if _is_code(obj):
        return obj.__module__ == module.__name__
    return _assignment_line(module, name) is not None


def _home(name: str, obj, documented: list[str], here: str) -> str | None:
    """The documented module other than ``here`` that defines ``obj``, if any."""
    if _is_code(obj):
        return obj.__module__ if obj.__module__ != here and obj.__module__ in documented else None
    for candidate in documented:
        module = importlib.import_module(candidate)
        if candidate != here and getattr(module, name, None) is obj and _defined_in(module, name):
            return candidate
    return None


def _line(module, name: str, obj) -> int:
    if _is_code(obj):
        try:
            return inspect.getsourcelines(getattr(obj, "py_func", obj))[1]
        except (OSError, TypeError):
            return 0
    return _assignment_line(module, name) or 0


def _attribute_docs(module_name: str) -> dict:
    from sphinx.pycode import ModuleAnalyzer, PycodeError

    try:
        return ModuleAnalyzer.for_module(module_name).find_attr_docs()
    except PycodeError:
        return {}


def _directive(module_name: str, name: str, obj) -> list[str]:
    """The directive that documents ``module_name.name``.

    A constant without a ``#:`` comment is declared with its value (a long value
    left out) rather than through autodoc, which would show the docstring of
    its type (an ndarray's, a dict's).
    """
    target = f"{module_name}.{name}"
    if inspect.isclass(obj):
        kind = "autoexception" if issubclass(obj, BaseException) else "autoclass"
        return [f".. {kind}:: {target}", "   :members:", ""]
    if _is_code(obj):
        return [f".. autofunction:: {target}", ""]
    if ("", name) in _attribute_docs(module_name):
        lines = [f".. autodata:: {target}"]
        return lines + (["   :no-value:"] if len(repr(obj)) > 100 else []) + [""]
    lines = [f".. py:data:: {name}", f"   :module: {module_name}"]
    if len(repr(obj)) <= 100:
        lines.append(f"   :value: {obj!r}")
    return lines + [""]


def _public_names(module) -> list[str]:
    """Names without a leading underscore that ``module`` itself defines (classes, functions, constants)."""
    names = []
    for name, obj in vars(module).items():
        if name.startswith("_") or inspect.ismodule(obj):
            continue
        if (_is_code(obj) or _assignment_line(module, name) is not None) and _defined_in(module, name):
            names.append(name)
    return names


def api_page(name: str, documented: list[str]) -> str:
    """The reST page of module ``name``.

    Its docstring, then what its ``__all__`` defines, in source order; a name it
    re-exports is linked to the documented module that defines it. The other
    public names it defines follow under their own heading: they are not part
    of the module's interface, but its docstrings and the derivations refer to them.
    """
    module = importlib.import_module(name)
    exported = getattr(module, "__all__", None)
    here, elsewhere = [], []
    for member in exported if exported is not None else _public_names(module):
        obj = _exported(module, member)
        home = None if _defined_in(module, member) else _home(member, obj, documented, name)
        if home:
            elsewhere.append((member, home))
        else:
            here.append((_line(module, member, obj), member, obj))
    internal = []
    if exported is not None:
        internal = [(_line(module, m, getattr(module, m)), m, getattr(module, m))
                    for m in _public_names(module) if m not in exported]
    lines = [name, "=" * len(name), "", f".. automodule:: {name}", ""]
    for _, member, obj in sorted(here, key=lambda item: item[0]):
        lines += _directive(name, member, obj)
    if elsewhere:
        lines += [".. rubric:: Also importable from here", ""]
        lines += [f"* :py:obj:`{member} <{home}.{member}>` (:mod:`{home}`)" for member, home in elsewhere]
        lines.append("")
    if internal:
        note = (f"Defined in :mod:`{name}` but not in its ``__all__``: helpers the module's own "
                "docstrings refer to.")
        lines += [".. rubric:: Not exported", "", note, ""]
        for _, member, obj in sorted(internal, key=lambda item: item[0]):
            lines += _directive(name, member, obj)
    return "\n".join(lines)


def register_aliases(app, env) -> list[str]:
    """Make every name a documented module imports resolve to where it is documented.

    A docstring's ``:class:`Resistance``` in :mod:`lubrication.registry` means the
    ``Resistance`` that module imports; Python finds it there, and so does Sphinx
    with these aliases (``lubrication.geometry.Resistance`` -> ``lubrication.geometry.Resistance``,
    members included). A class's attributes that have no entry of their own (a
    dataclass's fields, described in its Attributes section; what ``__init__``
    assigns) resolve to the class.
    """
    from sphinx.domains.python import ObjectEntry

    domain = env.get_domain("py")
    objects = domain.objects

    def alias(new: str, old: str) -> None:
        if new not in objects and old in objects:
            entry = objects[old]
            objects[new] = ObjectEntry(entry.docname, entry.node_id, entry.objtype, True)

    for full, entry in list(objects.items()):
        if entry.objtype not in ("class", "exception") or entry.aliased:
            continue
        for name in _attributes(_resolve(full)):
            if f"{full}.{name}" not in objects:
                objects[f"{full}.{name}"] = ObjectEntry(entry.docname, entry.node_id, "attribute", True)
    by_prefix: dict[str, list[str]] = {}
    for full in list(objects):
        by_prefix.setdefault(full.rsplit(".", 1)[0], []).append(full)
    documented = [m for _, modules in _groups(app) for m in modules]
    for name in documented:
        module = importlib.import_module(name)
        for member in dir(module):
            if member.startswith("_"):
                continue
            obj = _exported(module, member)
            if not _is_code(obj) or inspect.ismodule(obj):
                continue
            canonical = f"{obj.__module__}.{getattr(obj, '__qualname__', member)}"
            if canonical == f"{name}.{member}" or canonical not in objects:
                continue
            alias(f"{name}.{member}", canonical)
            for full in by_prefix.get(canonical, []):
                alias(f"{name}.{member}{full[len(canonical):]}", full)
    return []


_SELF_ASSIGNED = re.compile(r"^\s+self\.([A-Za-z]\w*)\s*(?::[^=\n]+)?=(?!=)", re.MULTILINE)


def _attributes(cls) -> list[str]:
    """The public attributes of ``cls``: a dataclass's fields, or what its ``__init__`` assigns to ``self``."""
    if not inspect.isclass(cls):
        return []
    if dataclasses.is_dataclass(cls):
        return [field.name for field in dataclasses.fields(cls)]
    init = cls.__dict__.get("__init__")
    try:
        return sorted(set(_SELF_ASSIGNED.findall(inspect.getsource(init)))) if init else []
    except (OSError, TypeError):
        return []


def _resolve(full: str):
    """The object named ``full`` ("package.module.Class"), or None."""
    parts = full.split(".")
    for cut in range(len(parts) - 1, 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for part in parts[cut:]:
                obj = getattr(obj, part)
        except AttributeError:
            return None
        return obj
    return None


def _groups(app) -> list[tuple[str, list[str]]]:
    return [(title, list(modules)) for title, modules in app.config.snail_api_groups]


def write_api_pages(app) -> None:
    """Write ``api/generated/<module>.rst`` for every module of ``snail_api_groups`` (only when changed)."""
    documented = [m for _, modules in _groups(app) for m in modules]
    folder = Path(app.srcdir) / "api" / "generated"
    folder.mkdir(parents=True, exist_ok=True)
    wanted = set()
    for name in documented:
        path = folder / f"{name}.rst"
        wanted.add(path.name)
        text = api_page(name, documented)
        if not path.exists() or path.read_text() != text:
            path.write_text(text)
    for stale in folder.glob("*.rst"):
        if stale.name not in wanted:
            stale.unlink()


# A role in a summary line, shown as a literal: out of its module, a short target would not resolve.
_ROLE = re.compile(r":[\w:]+:`~?([^`<]+?)(?: <[^`]+>)?`")


class ApiIndexDirective(_Generated):
    """``.. snail-api-index::``: each group of modules with a one-line summary and a toctree."""

    def lines(self) -> list[str]:
        lines = []
        for title, modules in _groups(self.env.app):
            lines += [title, "-" * len(title), "", ".. list-table::", "   :widths: 30 70", ""]
            for name in modules:
                doc = inspect.getdoc(importlib.import_module(name)) or ""
                first = _ROLE.sub(r"``\1``", doc.split("\n\n")[0].replace("\n", " "))
                lines += [f"   * - :mod:`{name}`", f"     - {_escape_text(first)}"]
            lines += ["", ".. toctree::", "   :hidden:", ""] + [f"   generated/{m}" for m in modules] + [""]
        return lines


# -- the gallery ---------------------------------------------------------------------------------------------

_SEEN: weakref.WeakSet = weakref.WeakSet()  # figures already shown, or left to the matplotlib scraper


def figure_scraper(block, block_vars, gallery_conf, **kwargs):
    """Images of the matplotlib ``Figure`` objects an example holds that pyplot does not manage.

    The project draws its figures without pyplot (:func:`dynamics.app.figures.trajectory_figure`);
    the gallery shows every such figure bound to a name in the example, once. It runs before
    sphinx-gallery's matplotlib scraper, which shows (and closes) pyplot's figures: those are
    remembered here, so that a closed pyplot figure is not taken for one of the project's.
    """
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    paths = []
    iterator = block_vars["image_path_iterator"]
    for value in list(block_vars["example_globals"].values()):
        if not isinstance(value, Figure) or value in _SEEN:
            continue
        _SEEN.add(value)
        if value.canvas.manager is None:
            path = next(iterator)
            value.savefig(path, dpi=100)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])


def rerun_unexecuted_examples(app) -> None:
    """Make sphinx-gallery run again the selected examples whose page was last built without running them.

    sphinx-gallery skips an example whose source has not changed since its page was
    written, whether or not it ran then: after a build that showed it without running it
    (``SNAIL_DOCS_EXAMPLES=none`` or a pattern that left it out), its page would keep
    no output. Every example here draws a figure, so a page without one was not run;
    removing its checksum makes the next build that selects it run it.
    """
    conf = app.config.sphinx_gallery_conf
    source = Path(app.srcdir) / conf["examples_dirs"]
    gallery = Path(app.srcdir) / conf["gallery_dirs"]
    selected = re.compile(conf["filename_pattern"])
    for example in sorted(source.glob("plot_*.py")):
        checksum = gallery / f"{example.name}.md5"
        figure = gallery / "images" / f"sphx_glr_{example.stem}_001.png"
        if selected.search(str(example)) and checksum.exists() and not figure.exists():
            checksum.unlink()


def setup(app):
    app.add_config_value("snail_api_groups", [], "env")
    app.add_directive("snail-cli", CliDirective)
    app.add_directive("snail-scene-reference", SceneReferenceDirective)
    app.add_directive("snail-force-models", ForceModelReferenceDirective)
    app.add_directive("snail-api-index", ApiIndexDirective)
    app.connect("builder-inited", write_api_pages)
    app.connect("builder-inited", rerun_unexecuted_examples, priority=400)  # before sphinx-gallery's
    app.connect("env-updated", register_aliases)
    app.connect("autodoc-process-docstring", _process_docstring, priority=400)  # before numpydoc
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


__all__ = ["cli_lines", "figure_scraper", "plain_text_docstring", "register_aliases", "rerun_unexecuted_examples",
           "rst_escape", "scene_lines", "setup", "write_api_pages"]
