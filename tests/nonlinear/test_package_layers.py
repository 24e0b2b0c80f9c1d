"""The imports of ``ringdamper.nonlinear`` flow one way, downwards through its layers
(docs/nonlinear_core.md, *Layout*).

Every module of ``ringdamper/nonlinear/`` is parsed with :mod:`ast` and every import it makes is read,
at module level and inside functions alike. A unit is a subpackage or a module directly under
``ringdamper/nonlinear/``; :data:`LAYERS` gives each its rank. A module may import the modules of its
own unit and those of units of strictly lower rank: units of the same rank do not import each other.
``ringdamper.nonlinear`` itself holds nothing to import.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = "ringdamper.nonlinear"
ROOT = Path(__file__).resolve().parents[2] / "ringdamper" / "nonlinear"

#: Rank of every unit of ``ringdamper.nonlinear``: lower ranks may not import higher ones.
LAYERS = {
    "fourier": 0,
    "normalisation": 0,
    "solvers": 0,
    "contact": 1,
    "harmonic_balance": 2,
    "indicators": 3,
    "time_domain": 3,
    "adaptive": 4,
    "stage": 5,
}


def _module_name(path: Path, root: Path) -> str:
    parts = path.relative_to(root).with_suffix("").parts
    return ".".join((PACKAGE,) + (parts[:-1] if parts[-1] == "__init__" else parts))


def _imported(tree: ast.Module, module: str, is_package: bool) -> list[tuple[int, str]]:
    """``(line, dotted name)`` of every module (or module attribute) ``tree`` imports, anywhere in
    it: ``from a.b import c`` gives ``a.b.c``, relative imports resolved against ``module``."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = module.split(".")
                anchor = anchor[:len(anchor) - node.level + (1 if is_package else 0)]
                base = ".".join(anchor + ([base] if base else []))
            found += [(node.lineno, f"{base}.{alias.name}") for alias in node.names]
    return found


def _unit(dotted: str) -> str | None:
    """The unit of ``ringdamper.nonlinear`` a dotted name lies in, ``""`` for the package itself,
    None outside it."""
    if dotted == PACKAGE:
        return ""
    if not dotted.startswith(PACKAGE + "."):
        return None
    return dotted[len(PACKAGE) + 1:].split(".")[0]


def layer_violations(root: Path = ROOT) -> list[str]:
    """Every import of a module under ``root`` that breaks the layer rule, as ``file:line: a -> b``."""
    violations = []
    for path in sorted(root.rglob("*.py")):
        module = _module_name(path, root)
        own = _unit(module)
        for line, dotted in _imported(ast.parse(path.read_text(), str(path)), module,
                                      path.name == "__init__.py"):
            target = _unit(dotted)
            if target is None or target == own:
                continue
            if target not in LAYERS or own == "" or LAYERS[target] >= LAYERS[own]:
                violations.append(f"{path.relative_to(root)}:{line}: {module} -> {dotted}")
    return violations


def test_every_unit_has_a_rank():
    units = {p.stem if p.suffix == ".py" else p.name for p in ROOT.iterdir()
             if (p.suffix == ".py" and p.stem != "__init__") or (p / "__init__.py").exists()}
    assert units == set(LAYERS)


def test_imports_flow_down_the_layers():
    assert layer_violations() == []


@pytest.mark.parametrize("source, line", [
    ("from ringdamper.nonlinear.stage import run_dnnm\n", 2),
    ("def f():\n    from ..harmonic_balance import epmc\n", 3),
    ("import ringdamper.nonlinear.time_domain.shooting\n", 2),
    ("from ringdamper.nonlinear import adaptive\n", 2),
])
def test_an_upward_import_is_found(tmp_path, source, line):
    """An upward import, at module level or inside a function, absolute or relative, is reported, and
    the downward one before it is not."""
    package = tmp_path / "ringdamper" / "nonlinear"
    (package / "contact").mkdir(parents=True)
    (package / "contact" / "x.py").write_text("from ringdamper.nonlinear.fourier import Fourier\n" + source)
    found = layer_violations(package)
    assert len(found) == 1 and found[0].startswith(f"contact/x.py:{line}: ringdamper.nonlinear.contact.x -> ")
