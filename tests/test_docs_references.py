"""Every reference the documentation names resolves: repository paths, ``module:function`` and dotted
names, ``tests/...::test`` ids, test names, rules, ``docs/x.md §n`` sections and markdown links.

Sources: ``README.md``, ``docs/*.md`` and ``docs/investigations/*.md`` (``CHANGELOG.md`` is history
and may name what is gone; the tables under ``docs/calibration/`` are generated) and the module
docstrings of ``ringdamper/`` (packages included). Paths under ``results/`` are generated and
exempt. A dotted name is resolved by importing its module and reading the attribute, except in the
modules of :data:`NO_IMPORT`, which run Snakemake on import and are read with :mod:`ast` instead.
"""
from __future__ import annotations

import ast
import importlib
import inspect
import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]

#: Modules that run Snakemake when imported: their names are looked up in their syntax tree.
NO_IMPORT = frozenset({"ringdamper.bench.__main__", "tools.scheduler_cost"})
#: Top-level folders of the repository a written path may start with.
ROOT_DIRS = ("ringdamper", "docs", "tests", "scripts", "workflow", "tools", "profiles", "envs", ".ci")
#: Endings of data files: a dotted word with one of them is a file name (``static.nc``), not code.
FILE_ENDINGS = frozenset({"nc", "vtu", "yaml", "yml", "csv", "png", "html", "md", "py", "smk", "json", "txt",
                          "tsv", "toml", "log"})
#: The packages and modules directly under ``ringdamper/``: ``fem.linalg.lowest_modes`` is
#: ``ringdamper.fem.linalg.lowest_modes``.
TOP_LEVEL = frozenset(p.stem for p in (ROOT / "ringdamper").iterdir()
                      if (p.suffix == ".py" and p.stem != "__init__") or (p / "__init__.py").exists())


@dataclass(frozen=True)
class Reference:
    """One reference found in a text: ``kind`` is ``path``, ``object``, ``test``, ``rule``, ``section``
    or ``link``; ``base`` is what a relative target is resolved against (the folder of a markdown file,
    the module of a docstring)."""

    kind: str
    target: str
    base: str = ""


PREFIXED_PATH = re.compile(r"(?<![\w./:-])((?:%s)/[\w./*{}-]*)" % "|".join(re.escape(d) for d in ROOT_DIRS))
TEST_ID = re.compile(r"(?<![\w./-])(tests/[\w/]+\.py)::(\w+)(?:::(\w+))?")
FILE_OBJECT = re.compile(r"`([\w/]+\.py):([\w.]+)`((?:\s*,\s*`[\w.]+`)*)")
DOTTED = re.compile(r"(?<![\w./-])((?:ringdamper|tools)(?:\.\w+)+)")
ROLE = re.compile(r":(?:mod|func|class|data|meth|attr|exc|obj):`~?([\w.]+)`")
CODE_SPAN = re.compile(r"(`+)([^`\n]+?)\1")
MARKDOWN_LINK = re.compile(r"\]\(([^)\s]+)\)")
SECTION = re.compile(r"(docs/\w+\.md)`?\s*§\s*(\d+(?:\.\d+)?)")
RULE = re.compile(r"\b(?:rule|checkpoint|rules)\s+`(\w+)`")
SPAN_DOTTED = re.compile(r"(\w+)((?:\.\w+)+)")
SPAN_SOURCE = re.compile(r"[\w/]+\.(?:py|smk)")
SPAN_TEST = re.compile(r"test_\w+")


def references(text: str, base: str = "") -> list[Reference]:
    """The references in ``text`` (markdown or a docstring); ``base`` is the folder of a markdown file
    relative to the repository, or the dotted name of the module whose docstring ``text`` is."""
    found = []
    for m in TEST_ID.finditer(text):
        found.append(Reference("test", f"{m[1]}::{m[2]}" + (f"::{m[3]}" if m[3] else "")))
    for m in PREFIXED_PATH.finditer(text):
        path = m[1].rstrip(".,;:")
        if path.rstrip("/") not in ROOT_DIRS:
            found.append(Reference("path", path))
    for m in FILE_OBJECT.finditer(text):
        names = [m[2]] + re.findall(r"`([\w.]+)`", m[3])
        found += [Reference("object", f"{m[1]}:{name}") for name in names]
    for m in DOTTED.finditer(text):
        if m[1].rsplit(".", 1)[1] not in FILE_ENDINGS:
            found.append(Reference("object", m[1]))
    for m in ROLE.finditer(text):
        found.append(Reference("object", m[1], base))
    for m in MARKDOWN_LINK.finditer(text):
        if not re.match(r"[a-z]+:|#", m[1]):
            found.append(Reference("link", m[1].split("#")[0], base))
    for m in SECTION.finditer(text):
        found.append(Reference("section", f"{m[1]} §{m[2]}"))
    for m in RULE.finditer(text):
        found.append(Reference("rule", m[1]))
    for m in CODE_SPAN.finditer(ROLE.sub("", text)):
        found += _span_references(m[2].strip(), base)
    return list(dict.fromkeys(found))


def _span_references(span: str, base: str) -> list[Reference]:
    """References written as a whole code span that need the span's boundaries to be told apart from
    prose: a source file without its folder (``test_gauge.py``, ``geometry/sector.py``), a dotted name
    under ``ringdamper`` without the prefix (``fem.linalg.lowest_modes``) and a test's name."""
    if SPAN_SOURCE.fullmatch(span) and not span.startswith(tuple(d + "/" for d in ROOT_DIRS)):
        return [Reference("path", span, base)]
    m = SPAN_DOTTED.fullmatch(span)
    if m and m[1] in TOP_LEVEL | set(_schema()["properties"]) and span.rsplit(".", 1)[1] not in FILE_ENDINGS:
        return [Reference("name", span)]
    if SPAN_TEST.fullmatch(span):
        return [Reference("test", span)]
    return []


# --------------------------------------------------------------------------------------------------
# Resolution


def resolves(ref: Reference) -> bool:
    """Whether ``ref`` names something that exists in the repository."""
    return {"path": _path_exists, "link": _link_exists, "object": _object_exists, "name": _name_exists,
            "test": _test_exists, "rule": _rule_exists, "section": _section_exists}[ref.kind](ref)


@cache
def _schema() -> dict:
    return yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())


def _config_key_exists(dotted: str) -> bool:
    """``dotted`` (``contact.friction_coefficient``) is a key of the configuration schema."""
    node = _schema()
    for part in dotted.split("."):
        while "$ref" in node:
            node = _schema()["$defs"][node["$ref"].rsplit("/", 1)[1]]
        node = node.get("properties", {}).get(part)
        if node is None:
            return False
    return True


def _name_exists(ref: Reference) -> bool:
    """A dotted name without its package: a configuration key, or code under ``ringdamper``."""
    return _config_key_exists(ref.target) or (ref.target.split(".")[0] in TOP_LEVEL
                                              and _dotted_exists(f"ringdamper.{ref.target}"))


def _path_exists(ref: Reference) -> bool:
    path = ref.target
    if "{" in path or path.startswith("results/"):
        return True  # a template of generated files
    candidates = [ROOT / path]
    if ref.base:  # a bare source file: beside the docstring's module, under ringdamper/, or by name
        module = _module_file(ref.base)
        if module is not None:
            candidates.append(module.parent / path)
    candidates.append(ROOT / "ringdamper" / path)
    if "*" in path:
        return any(any(ROOT.glob(str(c.relative_to(ROOT)))) for c in candidates if ROOT in c.parents)
    if any(c.exists() for c in candidates):
        return True
    return "/" not in path and any(p.name == path for p in _repository_files())


def _link_exists(ref: Reference) -> bool:
    path = (ROOT / ref.base / ref.target).resolve()
    return path.is_relative_to(ROOT / "results") or path.exists()


@cache
def _repository_files() -> tuple[Path, ...]:
    return tuple(p for d in ("ringdamper", "scripts", "tools", "tests", "workflow")
                 for p in (ROOT / d).rglob("*") if p.suffix in (".py", ".smk"))


def _module_file(dotted: str) -> Path | None:
    """The file of module ``dotted`` (a package's ``__init__.py``), or None."""
    stem = ROOT.joinpath(*dotted.split("."))
    for path in (stem.with_suffix(".py"), stem / "__init__.py"):
        if path.exists():
            return path
    return None


def _object_exists(ref: Reference) -> bool:
    target = ref.target
    if ":" in target:  # path/to/module.py:name, the path from the repository or from ringdamper/
        path, name = target.split(":")
        for file in (ROOT / path, ROOT / "ringdamper" / path):
            if file.exists():
                return _name_in_file(file, name)
        # a module named by its path within its package (``trial.py:run_trial``)
        return any(_name_in_file(file, name) for file in _repository_files() if file.match(path))
    target = target.lstrip(".")
    if ref.base:  # a docstring's role: relative to its module, then its package, then absolute
        module = ref.base.split(".")
        scopes = [".".join(module[:i]) for i in range(len(module), 0, -1)] + ["ringdamper", ""]
        return any(_dotted_exists(f"{scope}.{target}" if scope else target) for scope in scopes)
    return _dotted_exists(target)


def _dotted_exists(dotted: str) -> bool:
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        module = ".".join(parts[:i])
        file = _module_file(module)
        if file is None:
            continue
        rest = parts[i:]
        if not rest:
            return True
        if module in NO_IMPORT or not module.startswith("ringdamper"):
            return _name_in_file(file, ".".join(rest))
        obj = importlib.import_module(module)
        for name in rest:
            if not _has_attribute(obj, name):
                return False
            obj = getattr(obj, name, None)
        return True
    return False


def _has_attribute(obj, name: str) -> bool:
    """``name`` is an attribute of ``obj``, a dataclass field or annotation of a class, or an attribute
    its methods set on ``self``."""
    if hasattr(obj, name):
        return True
    if not inspect.isclass(obj):
        return False
    for cls in obj.__mro__:
        if name in getattr(cls, "__annotations__", {}):
            return True
        try:
            if re.search(rf"\bself\.{name}\s*=", inspect.getsource(cls)):
                return True
        except (OSError, TypeError):
            pass
    return False


@cache
def _tree(file: Path) -> ast.Module:
    return ast.parse(file.read_text(), filename=str(file))


def _defined_names(body) -> dict[str, ast.AST]:
    """The names a module or class body binds: functions, classes, assignments, imports."""
    names = {}
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names[node.name] = node
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in node.targets if isinstance(node, ast.Assign) else [node.target]:
                for n in ast.walk(target):
                    if isinstance(n, ast.Name):
                        names[n.id] = node
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            for alias in node.names:
                names[(alias.asname or alias.name).split(".")[0]] = node
    return names


def _name_in_file(file: Path, dotted: str) -> bool:
    """``dotted`` (``name`` or ``Class.member``) is bound at the top of ``file``, without importing it;
    a dataclass field or a ``self.member`` assignment counts as a member."""
    body = _tree(file).body
    *classes, last = dotted.split(".")
    for name in classes:
        node = _defined_names(body).get(name)
        if not isinstance(node, ast.ClassDef):
            return False
        body = node.body
    if last in _defined_names(body):
        return True
    return bool(classes) and any(isinstance(n, ast.Attribute) and n.attr == last and isinstance(n.value, ast.Name)
                                 and n.value.id == "self" for n in ast.walk(ast.Module(body=body, type_ignores=[])))


@cache
def _test_names() -> frozenset[str]:
    return frozenset(node.name for file in (ROOT / "tests").rglob("test_*.py") for node in ast.walk(_tree(file))
                     if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name.startswith(("test", "Test")))


def _test_exists(ref: Reference) -> bool:
    if "::" not in ref.target:
        return ref.target in _test_names()
    path, *names = ref.target.split("::")
    return (ROOT / path).exists() and _name_in_file(ROOT / path, ".".join(names))


@cache
def _rules() -> frozenset[str]:
    text = "\n".join(p.read_text() for p in [ROOT / "Snakefile", *(ROOT / "workflow" / "rules").glob("*.smk")])
    return frozenset(re.findall(r"^(?:rule|checkpoint)\s+(\w+)\s*:", text, flags=re.M))


def _rule_exists(ref: Reference) -> bool:
    return ref.target in _rules()


def _section_exists(ref: Reference) -> bool:
    """``docs/x.md §n`` or ``§n.m``: a heading numbered so, or for ``§n.m`` where section n has no
    numbered subheadings, item m of a numbered list in section n."""
    path, number = ref.target.split(" §")
    file = ROOT / path
    if not file.exists():
        return False
    text = file.read_text()
    if re.search(rf"^#+\s+{re.escape(number)}[.\s]", text, flags=re.M):
        return True
    top, _, sub = number.partition(".")
    section = re.search(rf"^(#+)\s+{top}[.\s].*?(?=^\1\s|\Z)", text, flags=re.M | re.S)
    if not sub or section is None or re.search(rf"^#+\s+{top}\.\d", text, flags=re.M):
        return False
    return re.search(rf"^\s*{sub}\.\s", section[0], flags=re.M) is not None


# --------------------------------------------------------------------------------------------------
# The sources


def _module_name(file: Path) -> str:
    parts = file.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def sources() -> dict[str, tuple[str, str]]:
    """Every documentation text by its file: (text, base of its relative references)."""
    texts = {}
    pages = [*sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "docs" / "investigations").glob("*.md"))]
    for file in [ROOT / "README.md", *pages]:
        texts[str(file.relative_to(ROOT))] = (file.read_text(), str(file.parent.relative_to(ROOT)))
    for file in sorted((ROOT / "ringdamper").rglob("*.py")):
        docstring = ast.get_docstring(_tree(file), clean=False)
        if docstring:
            texts[str(file.relative_to(ROOT))] = (docstring, _module_name(file))
    return texts


def unresolved(text: str, base: str) -> list[str]:
    return [f"{ref.kind} {ref.target}" for ref in references(text, base) if not resolves(ref)]


@pytest.mark.parametrize("source", sorted(sources()))
def test_every_reference_resolves(source):
    text, base = sources()[source]
    missing = list(unresolved(text, base))
    assert not missing, f"{source} names what does not exist:\n" + "\n".join(missing)


def test_the_sources_are_scanned():
    """The scan sees the documentation (a pattern that matched nothing would pass every source)."""
    refs = [ref for text, base in sources().values() for ref in references(text, base)]
    counts = {kind: sum(ref.kind == kind for ref in refs) for kind in
              ("path", "object", "name", "test", "rule", "section", "link")}
    assert all(n > 0 for n in counts.values()), counts


# --------------------------------------------------------------------------------------------------
# The extractor on synthetic texts: a good reference passes, a bad one is caught, prose is left alone


@pytest.mark.parametrize(("text", "base", "expected"), [
    ("`ringdamper/nonlinear/harmonic_balance/epmc.py`", "", []),
    ("see ringdamper/nonlinear/epmcc.py.", "", ["path ringdamper/nonlinear/epmcc.py"]),
    ("`workflow/rules/*.smk`", "", []),
    ("`workflow/rules/*.smx`", "", ["path workflow/rules/*.smx"]),
    ("`results/geometry/{gid}/dnnm.nc`, `results/nothing.csv`", "", []),
    ("`nonlinear/harmonic_balance/epmc.py:epmc`, `linear_limit`", "", []),
    ("`nonlinear/harmonic_balance/epmc.py:epmc`, `old_epmc`", "",
     ["object nonlinear/harmonic_balance/epmc.py:old_epmc"]),
    ("`campaign/kriging/gp.py:GPModel.predict`", "", []),
    ("`campaign/kriging/gp.py:GPModel.forecast`", "", ["object campaign/kriging/gp.py:GPModel.forecast"]),
    ("(`ringdamper.nonlinear.harmonic_balance.epmc.epmc`)", "", []),
    ("ringdamper.nonlinear.harmonic_balance.epmc.EPMC", "", ["object ringdamper.nonlinear.harmonic_balance.epmc.EPMC"]),
    ("`fem.linalg.lowest_modes`", "", []),
    ("`fem.linalg.highest_modes`", "", ["name fem.linalg.highest_modes"]),
    ("`static.nc`, `config.yaml`, `contact.friction_coefficient`, ``static.method``", "", []),
    ("`contact.friction_coeff`", "", ["name contact.friction_coeff"]),
    ("`trial.py:run_trial`", "", []),
    ("`python -m tools.scheduler_cost`", "", []),
    ("`tools.scheduler_cost.no_such_name`", "", ["object tools.scheduler_cost.no_such_name"]),
    ("`tests/nonlinear/test_gauge.py::test_no_such_test`", "",
     ["test tests/nonlinear/test_gauge.py::test_no_such_test"]),
    ("test `test_the_sources_are_scanned`", "", []),
    ("test `test_of_nothing`", "", ["test test_of_nothing"]),
    ("`test_gauge.py`", "", []),
    ("`test_gone.py`", "", ["path test_gone.py"]),
    ("rule `kriging`, rule `krigin`", "", ["rule krigin"]),
    ("`docs/design.md` §10, docs/design.md §3.4", "", []),
    ("`docs/design.md` §42", "", ["section docs/design.md §42"]),
    ("![figure](figures/epmc_time_domain.png) [x](https://example.org)", "docs", []),
    ("[figure](figures/missing.png)", "docs", ["link figures/missing.png"]),
    ("the stage (:mod:`.stage`) and :func:`~ringdamper.status.usable_status`", "ringdamper.modal", []),
    ("the solver (:mod:`.solverr`)", "ringdamper.static", ["object .solverr"]),
])
def test_extractor_catches_bad_references(text, base, expected):
    assert unresolved(text, base) == expected


def test_no_import_modules_are_not_imported():
    """Resolving a name in a module that runs Snakemake on import reads its source only."""
    import sys

    assert resolves(Reference("object", "tools.scheduler_cost.report"))
    assert "tools.scheduler_cost" not in sys.modules
