"""Mesh convergence: the default mesh's 1D-ND3 frequency is within 1 % of the finest affordable level."""
import pytest

from ringdamper.studies.mesh_convergence import refined, target_frequency


@pytest.mark.slow
def test_default_mesh_within_one_percent_of_refined(campaign_config):
    default = target_frequency(campaign_config)
    fine = target_frequency(refined(campaign_config, 2))   # 8x the elements, ~44k DoFs
    assert fine["dofs"] > 6 * default["dofs"]
    assert default["frequency_hz"] == pytest.approx(fine["frequency_hz"], rel=0.01)
    # convergence from above (a displacement-based FE model is too stiff)
    assert default["frequency_hz"] > fine["frequency_hz"]
