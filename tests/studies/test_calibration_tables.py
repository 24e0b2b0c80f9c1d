"""The contact calibration's Markdown tables: unit conversions, ordering, and the committed page
docs/calibration/tables.md regenerated from the committed CSVs (so the two cannot drift)."""
from pathlib import Path

import pandas as pd

from ringdamper.studies.calibration_tables import calibration_tables, markdown_table

DOCS = Path(__file__).resolve().parents[2] / "docs" / "calibration"
STAGES = ("coarse", "refine", "harmonics_A", "harmonics_B")


def test_rows_are_sorted_by_objective_and_converted_to_percent_and_mm():
    rows = pd.read_csv(DOCS / "refine.csv")
    lines = markdown_table(rows).splitlines()[2:]
    assert len(lines) == len(rows)
    best = rows.loc[rows.objective.idxmin()]
    cells = [c.strip() for c in lines[0].strip("|").split("|")]
    assert float(cells[5]) == round(100 * best.zeta_max, 3)          # ζ_max in %
    assert float(cells[6]) == round(1e3 * best.q_at_zeta_max, 3)     # q* in mm
    assert float(cells[11]) == round(best.objective, 3)
    objectives = [float(line.strip("|").split("|")[11]) for line in lines]
    assert objectives == sorted(objectives)


def test_committed_tables_page_is_the_rendering_of_the_committed_csvs():
    page = calibration_tables(*(DOCS / f"{s}.csv" for s in STAGES))
    assert (DOCS / "tables.md").read_text(encoding="utf-8") == page
