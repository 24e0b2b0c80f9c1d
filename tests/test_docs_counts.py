"""The README's and the report's counts and times are the configuration's defaults or the generated
performance page's figures (docs/performance.md, ringdamper.performance), never numbers copied by hand.

Counts of rings are written with what they count: ``N validation rings``, ``N initial training rings``,
``at most N training rings``, ``N rings a round``, ``N factorial + M LHS`` (the paper design); a bare
``N training rings`` is refused, since the adaptive design's count is an outcome, not a default (the
performance page has it). ``N jobs`` and ``X min`` must be figures of the performance page.
"""
import re
from functools import cache
from pathlib import Path

import pytest

from ringdamper.config import load_config
from ringdamper.performance import read_markdown

ROOT = Path(__file__).resolve().parents[1]
RINGS = r"(?:rings?|geometries)"
SOURCES = [ROOT / "README.md", *sorted((ROOT / "workflow" / "report").glob("*.rst"))]


@cache
def expected_counts() -> dict[str, int]:
    """What each phrase counts, from the defaults of ``config.yaml`` (section ``sampling``)."""
    s = load_config()["sampling"]
    return {"validation": s["n_lhs_validation"] + len(s["named_validation"]),
            "initial": s["adaptive"]["n_initial"], "budget": s["adaptive"]["n_max"],
            "batch": s["adaptive"]["batch"], "factorial": len(s["factorial_levels"]) ** 3,
            "lhs": s["n_lhs_training"]}


@cache
def page_figures() -> set[str]:
    """The values printed on the performance page."""
    return set(read_markdown((ROOT / "docs" / "performance.md").read_text()).values())


PHRASES = {  # pattern -> what its number must equal
    rf"(\d+) validation {RINGS}": "validation",
    rf"(\d+) initial training {RINGS}": "initial",
    rf"at most (\d+) training {RINGS}": "budget",
    rf"(\d+) {RINGS} a round": "batch",
    r"(\d+) factorial": "factorial",
    r"(\d+) LHS": "lhs",
}


def wrong_figures(text: str) -> list[str]:
    """Each count or time of ``text`` that is neither the configuration's default it names nor a
    figure of the performance page."""
    text = re.sub(r"\s+", " ", text)
    wrong = []
    for pattern, key in PHRASES.items():
        wrong += [f"{m[0]!r}: the default is {expected_counts()[key]}"
                  for m in re.finditer(pattern, text) if int(m[1]) != expected_counts()[key]]
    wrong += [f"{m[0]!r}: a bare count of training rings (say which: initial, at most)"
              for m in re.finditer(rf"(?<!at most )\b(\d+) training {RINGS}", text)]
    for pattern in (r"(\d+) jobs", r"(\d+(?:\.\d+)?) min\b"):
        wrong += [f"{m[0]!r}: not a figure of docs/performance.md" for m in re.finditer(pattern, text)
                  if m[1] not in page_figures()]
    return wrong


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: str(p.relative_to(ROOT)))
def test_counts_and_times_come_from_the_config_or_the_performance_page(source):
    assert not wrong_figures(source.read_text())


def test_the_readme_states_the_default_design():
    """The README says how many rings the default design starts from, adds and may reach, and how
    many validate it (so the check above has something to check)."""
    text = re.sub(r"\s+", " ", (ROOT / "README.md").read_text())
    for pattern in list(PHRASES)[:4]:
        assert re.search(pattern, text), pattern


@pytest.mark.parametrize("text", [
    "the paper design's 100 training rings", "100 training geometries", "19 validation rings",
    "at most 90 training rings", "in 8.2 min", "220 jobs", "27 factorial + 70 LHS",
])
def test_a_number_written_by_hand_is_caught(text):
    assert wrong_figures(text)


def test_the_defaults_pass():
    n = expected_counts()
    for text in (f"{n['validation']} validation rings",
                 f"{n['initial']} initial training rings, {n['batch']} rings a round, "
                 f"at most {n['budget']} training rings",
                 f"{n['factorial']} factorial + {n['lhs']} LHS"):
        assert not wrong_figures(text), text
