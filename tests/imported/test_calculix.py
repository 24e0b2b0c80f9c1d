"""The import report's frequencies on the example blisk against CalculiX (an independent FE code) on the
same mesh: cyclic symmetry, every nodal diameter 0..N/2, at rest and prestressed at the operating speed.

CalculiX integrates C3D10 with 4 Gauss points (stiffness and mass); the import report's default is
the exact consistent mass (degree 4), which differs by up to 4.6e-4 on this coarse mesh. The
comparison is made with the same 4-point rule (intorder 2), where the two codes are the same
discretisation: at rest they agree to the 7 digits of CalculiX's .dat output. Prestressed, CalculiX
solves a geometrically nonlinear static state and takes its tangent; the report's model is the
linear prestress of docs/model.md; at 2081 rpm they agree within 1e-4
(docs/investigations/2026-12-01-imported-calculix.md).
"""
import os
import shutil

import numpy as np
import pytest

from ringdamper.fem.prestress import rpm_to_rad_s
from ringdamper.imported.calculix import run_cyclic
from ringdamper.imported.report import nd_frequencies
from ringdamper.imported.sector import load_imported_sector

CALCULIX_RULE = 2   # scikit-fem's 4-point tetrahedron rule, CalculiX's for C3D10
N_MODES = 3

pytestmark = [pytest.mark.slow, pytest.mark.skipif(shutil.which("ccx") is None and not os.environ.get("CI"),
                                reason="CalculiX (Debian calculix-ccx) is not installed; .ci/run installs it")]


@pytest.mark.parametrize("rpm, tolerance", [(0.0, 1e-6), (2081.0, 1e-4)])
def test_frequencies_match_calculix_cyclic_symmetry(imported, campaign_config, rpm, tolerance):
    sector = load_imported_sector(imported, campaign_config["material"], intorder=CALCULIX_RULE)
    theirs = run_cyclic(sector, N_MODES, rpm_to_rad_s(rpm))
    rows = nd_frequencies(sector, [rpm], N_MODES)
    assert sorted(theirs) == list(range(sector.n_sectors // 2 + 1))
    ours = np.array([[r["frequency_hz"] for r in rows if r["nd"] == nd] for nd in sorted(theirs)])
    reference = np.array([theirs[nd][:N_MODES] for nd in sorted(theirs)])
    assert np.max(np.abs(ours / reference - 1)) < tolerance
