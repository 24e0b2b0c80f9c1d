"""Functions longer than the project's limit (80 lines) in the Python sources of ``ringdamper/``,
``scripts/`` and ``tools/``: the length of a function (``def`` or ``async def``, methods and nested
functions included) is the number of lines from its ``def`` line to its last line (decorators not
counted). ``make lint`` runs it; it prints every offender as ``module:function  N lines`` and exits 1
when there is one.

    python -m tools.function_lengths [--max-lines 80] [ROOT ...]
"""
from __future__ import annotations

import argparse
import ast
import sys
from pathlib import Path

MAX_LINES = 80
ROOTS = ("ringdamper", "scripts", "tools")


def functions(tree: ast.AST, prefix: str = ""):
    """(qualified name, line count) of every function in ``tree``: ``Class.method``, ``outer.inner``."""
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield prefix + node.name, node.end_lineno - node.lineno + 1
            yield from functions(node, f"{prefix}{node.name}.")
        elif isinstance(node, ast.ClassDef):
            yield from functions(node, f"{prefix}{node.name}.")
        else:
            yield from functions(node, prefix)


def module_name(path: Path, base: Path) -> str:
    """Dotted module name of ``path`` relative to ``base`` (``ringdamper/geometry/sector.py`` ->
    ``ringdamper.geometry.sector``)."""
    parts = path.relative_to(base).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def offenders(roots, base: Path, max_lines: int = MAX_LINES) -> list[tuple[str, int]]:
    """(``module:function``, line count) of every function over ``max_lines`` lines in the ``*.py``
    files under ``roots`` (paths relative to ``base``), by module then position."""
    found = []
    for root in roots:
        for path in sorted((base / root).rglob("*.py")):
            tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
            found += [(f"{module_name(path, base)}:{name}", n) for name, n in functions(tree) if n > max_lines]
    return found


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("roots", nargs="*", default=list(ROOTS), help="folders to scan (default: %(default)s)")
    parser.add_argument("--max-lines", type=int, default=MAX_LINES)
    args = parser.parse_args(argv)
    found = offenders(args.roots, Path.cwd(), args.max_lines)
    for name, n in found:
        print(f"{name}  {n} lines")
    if found:
        print(f"{len(found)} function(s) over {args.max_lines} lines", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
