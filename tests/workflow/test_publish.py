"""The one route from a study's results to docs/ (ringdamper.publish, docs/artifacts.yaml): the
manifest lists every committed artifact exactly once, each from a result a rule of the workflow
makes, and publishing copies exactly its entries or, with a result missing, nothing."""
from pathlib import Path

import pytest

from ringdamper.publish import ManifestError, main, publish, read_manifest
from tests.snakemake_run import REPO, failure_tail, run_snakemake

FOLDERS = ("calibration", "fidelity", "epmc_time_domain", "figures", "adaptive")
#: generated pages directly under docs/
PAGES = ("performance.md",)


def _artifacts() -> list[str]:
    return [artifact for entries in read_manifest(REPO / "docs" / "artifacts.yaml").values()
            for artifact in entries]


def test_the_manifest_lists_every_committed_artifact_once():
    docs = REPO / "docs"
    committed = {str(p.relative_to(docs)) for folder in FOLDERS for p in (docs / folder).rglob("*") if p.is_file()}
    committed |= {page for page in PAGES if (docs / page).is_file()}
    listed = _artifacts()
    assert len(listed) == len(set(listed))
    assert sorted(committed - set(listed)) == [], "committed but not in docs/artifacts.yaml"
    assert sorted(set(listed) - committed) == [], "in docs/artifacts.yaml but not committed"


def test_every_result_of_the_manifest_is_made_by_a_rule(tmp_path):
    """The DAG of every listed result as a target, built and printed (``--dag``): a name no rule writes
    fails it. The DAG alone answers that; a dry run would also walk the schedule."""
    sources = [tmp_path / source for entries in read_manifest(REPO / "docs" / "artifacts.yaml").values()
               for source in entries.values()]
    run = run_snakemake(tmp_path, REPO / "config.yaml", "--dag", "dot", *sources)
    assert run.returncode == 0, failure_tail(run)


def _manifest(tmp_path, text) -> Path:
    path = tmp_path / "artifacts.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("text, twice", [
    ("a:\n  figures/x.png: one/x.png\n  figures/x.png: two/x.png\n", "figures/x.png"),
    ("a:\n  figures/x.png: one/x.png\nb:\n  figures/x.png: two/x.png\n", "figures/x.png"),
    ("a:\n  figures/x.png: one/x.png\na:\n  figures/y.png: one/y.png\n", "a"),
])
def test_an_artifact_listed_twice_is_refused(tmp_path, text, twice):
    with pytest.raises(ManifestError, match=twice):
        read_manifest(_manifest(tmp_path, text))


def test_publish_copies_exactly_the_routes_entries(tmp_path):
    results, docs = tmp_path / "results", tmp_path / "docs"
    for name, content in (("studies/a/x.csv", "x\n1\n"), ("studies/b/p.png", "png"), ("fidelity/f.csv", "f")):
        (results / name).parent.mkdir(parents=True, exist_ok=True)
        (results / name).write_text(content)
    manifest = _manifest(tmp_path, "studies:\n  calibration/x.csv: studies/a/x.csv\n"
                                   "  figures/method_p.png: studies/b/p.png\n"
                                   "fidelity:\n  fidelity/f.csv: fidelity/f.csv\n")
    written = publish("studies", results, docs, manifest)
    assert sorted(written) == [docs / "calibration" / "x.csv", docs / "figures" / "method_p.png"]
    assert sorted(str(p.relative_to(docs)) for p in docs.rglob("*") if p.is_file()) == [
        "calibration/x.csv", "figures/method_p.png"]
    assert (docs / "calibration" / "x.csv").read_text() == "x\n1\n"


def test_a_missing_result_is_named_and_nothing_is_copied(tmp_path):
    results, docs = tmp_path / "results", tmp_path / "docs"
    (results / "studies").mkdir(parents=True)
    (results / "studies" / "x.csv").write_text("x")
    manifest = _manifest(tmp_path, "studies:\n  calibration/x.csv: studies/x.csv\n"
                                   "  calibration/y.csv: studies/y.csv\n")
    with pytest.raises(ManifestError, match=r"studies/y\.csv") as err:
        publish("studies", results, docs, manifest)
    assert "x.csv" not in str(err.value) and "make studies" in str(err.value)
    assert not docs.exists()
    with pytest.raises(ManifestError, match="one of studies"):
        publish("fidelity", results, docs, manifest)


def test_the_command_line_reports_a_missing_result(tmp_path, capsys):
    assert main(["fidelity", "--results", str(tmp_path / "nothing")]) == 1
    assert "missing results" in capsys.readouterr().err
