"""Publish a study's results as the committed artifacts under ``docs/``: the one route from
``results/`` to ``docs/calibration``, ``docs/fidelity``, ``docs/epmc_time_domain``,
``docs/figures`` and ``docs/adaptive`` (docs/design.md, "Committed study artifacts").

The manifest ``docs/artifacts.yaml`` lists, per route (the Makefile target that runs the study),
every committed artifact (path under ``docs/``) and the result it is a plain copy of (path under the
results folder). Run from the repository root, after the study::

    python -m ringdamper.publish studies [--results results]
"""
from __future__ import annotations

import argparse
import shutil
import sys
from pathlib import Path

import yaml

MANIFEST = Path("docs/artifacts.yaml")


class ManifestError(ValueError):
    """A manifest with a duplicate entry, or a result missing for publishing."""


class _UniqueKeyLoader(yaml.SafeLoader):
    """A YAML loader that refuses a key given twice in one mapping (plain YAML keeps the last)."""

    def construct_mapping(self, node, deep=False):
        keys = [self.construct_object(key, deep=deep) for key, _ in node.value]
        twice = sorted({str(k) for k in keys if keys.count(k) > 1})
        if twice:
            raise ManifestError(f"{node.start_mark.name}: listed twice: {', '.join(twice)}")
        return super().construct_mapping(node, deep=deep)


def read_manifest(path=MANIFEST) -> dict[str, dict[str, str]]:
    """route -> {artifact under docs/: result under the results folder}; an artifact listed twice, in
    one route or in two, is an error."""
    with open(path) as fh:
        manifest = yaml.load(fh, Loader=_UniqueKeyLoader)
    owner = {}
    for route, entries in manifest.items():
        for artifact in entries:
            if artifact in owner:
                raise ManifestError(f"{path}: {artifact} listed in routes {owner[artifact]} and {route}")
            owner[artifact] = route
    return manifest


def publish(route: str, results="results", docs="docs", manifest=MANIFEST) -> list[Path]:
    """Copy every result of ``route`` to its artifact under ``docs`` (nothing is copied unless every
    result exists); return the artifacts written."""
    entries = read_manifest(manifest)
    if route not in entries:
        raise ManifestError(f"route {route!r} is not in {manifest}: one of {', '.join(entries)}")
    pairs = [(Path(results) / source, Path(docs) / artifact) for artifact, source in entries[route].items()]
    missing = [str(source) for source, _ in pairs if not source.is_file()]
    if missing:
        raise ManifestError(f"route {route!r}: missing results (run `make {route}` first): {', '.join(missing)}")
    for source, artifact in pairs:
        artifact.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, artifact)
    return [artifact for _, artifact in pairs]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("route", help=f"a route of {MANIFEST}")
    parser.add_argument("--results", default="results", help="the results folder (default: results)")
    args = parser.parse_args(argv)
    try:
        written = publish(args.route, args.results)
    except ManifestError as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    print(f"{len(written)} artifacts of {args.route!r} published under docs/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
