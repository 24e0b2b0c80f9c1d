"""The modal stage's frequency normalisation: the ND diagram's omega0 is 2.195 f / f_cross, f_cross the
target mode's frequency where the engine-order line f = EO Ω / 2π crosses its Campbell curve."""
import numpy as np
import pytest

from ringdamper.modal.stage import run_modal_stage
from ringdamper.nonlinear.normalisation import PAPER_NORMALISED_FREQUENCY


@pytest.fixture(scope="module")
def modal(small_config):
    return run_modal_stage(small_config)


def test_reference_frequency_is_the_engine_order_crossing(modal):
    res, nd = modal.resonance, modal.nd_diagram
    f_cross = res["engine_order"] * res["speed_rpm"] / 60.0  # on the EO line at the crossing speed
    assert nd.attrs["reference_frequency_hz"] == res["frequency_hz"]
    assert res["frequency_hz"] == pytest.approx(f_cross, rel=1e-9)
    omega0 = PAPER_NORMALISED_FREQUENCY * nd["frequency"].values / f_cross
    np.testing.assert_allclose(nd["omega0"].values, omega0, rtol=1e-9)


def test_omega0_names_the_crossing_frequency(modal):
    long_name = modal.nd_diagram["omega0"].attrs["long_name"]
    assert "f_cross" in long_name and "crossing" in long_name and "stuck" not in long_name
