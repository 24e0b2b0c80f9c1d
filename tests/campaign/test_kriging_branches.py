"""Kriging of data that scatter between solution branches (ringdamper.campaign.kriging), on stored
campaign data: ζ at α = 1.366e-4 kg^0.5 m (index 25 of the campaign grid) on the 100 training rings of
two from-scratch runs of the paper design (`data/paper_zeta_branches.csv`). The runs differ in one ring
that matters: t035, κ = (0.242, -0.432, -0.901), was held by the gauge on the first run (ζ = 1.52e-3)
and free on the second (ζ = 0.72e-3); every other ring moved by less than 1.5e-5.

With the library's defaults (θ ≥ 0.1, no nugget) the likelihood pins θ₁ on its floor and stretches θ₂,
θ₃ to 4-10: t035 then weighs -1.26 and -1.21 in the prediction at κ = (0.195, -1, 1), 1.9 away from it, and the two
runs predict 1.16e-3 and 2.34e-3 there (computed: 1.42e-3), the second a spurious optimum. The campaign's
settings (config.yaml: θ ≥ 0.3, estimated nugget) take the scatter as noise (docs/surrogate.md, *Branch
scatter*)."""

import itertools
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from ringdamper.campaign import kriging as K
from ringdamper.campaign.kriging.gp import _scaled_d2, _squared_differences, correlation
from ringdamper.campaign.kriging.transform import Transform

DATA = pd.read_csv(Path(__file__).parent / "data" / "paper_zeta_branches.csv")
CAMPAIGN = yaml.safe_load((Path(__file__).parents[2] / "config.yaml").read_text())["surrogate"]
# θ ≥ 0.1, ν = 1e-12, 8 starts
LIBRARY_DEFAULTS = {k: K.DEFAULT_SETTINGS[k] for k in ("scale_bounds", "nugget", "n_starts")}
CORNER = np.array([[0.195343, -1.0, 1.0]])  # the second run's predicted optimum
ZETA_COMPUTED = 1.4200458612073227e-3  # ζ of the ring computed at CORNER, same amplitude (status 3)
X = DATA[["kappa1", "kappa2", "kappa3"]].to_numpy()


def kriging_weights(model: K.GPModel, points: np.ndarray) -> np.ndarray:
    """(N, m) ordinary-Kriging weights wᵢ(x₀) at the fitted θ, ν: ẑ(x₀) = Σᵢ wᵢ(x₀) zᵢ, Σᵢ wᵢ = 1,
    w = R⁻¹r₀ + R⁻¹1 (1 − 1ᵀR⁻¹r₀) / 1ᵀR⁻¹1 (the linear sensitivity of the prediction to each datum)."""
    R = correlation(model.kernel, _scaled_d2(_squared_differences(model.x, model.x), model.scale))
    R[np.diag_indices_from(R)] += model.nugget
    r = correlation(model.kernel, _scaled_d2(_squared_differences(points, model.x), model.scale))
    Rinv_r, Rinv_1 = np.linalg.solve(R, r.T), np.linalg.solve(R, np.ones(len(model.x)))
    return Rinv_r + np.outer(Rinv_1, 1.0 - Rinv_r.sum(axis=0)) / Rinv_1.sum()


def fit_run(run: str, settings: dict):
    """The campaign's model of ζ on one run's rings (log transform, c = max ζ): (model, prediction of ζ
    at CORNER, weight of t035 there)."""
    y = DATA[f"zeta_{run}"].to_numpy()
    transform = Transform.for_data(settings["transform"]["zeta"], y, settings["log_offset"], y.max())
    model, _ = K.fit_model(X, transform.forward(y), settings)
    w = kriging_weights(model, CORNER)[:, 0]
    np.testing.assert_allclose(w.sum(), 1.0, atol=1e-9)
    t035 = int(np.flatnonzero(DATA["gid"] == "t035")[0])
    return model, float(transform.inverse(model.predict(CORNER, with_std=False)[0])[0]), float(w[t035])


@pytest.fixture(scope="module")
def fits():
    return {(run, name): fit_run(run, {**CAMPAIGN, **extra})
            for run, (name, extra) in itertools.product(("first", "second"),
                                                        (("campaign", {}), ("library", LIBRARY_DEFAULTS)))}


def test_the_data_differ_in_one_ring_that_changed_branch():
    change = np.abs(DATA["zeta_second"] - DATA["zeta_first"])
    assert DATA["gid"][int(np.argmax(change))] == "t035" and change.max() > 7e-4
    assert np.sort(change)[-2] < 1.5e-5
    t035 = DATA[DATA["gid"] == "t035"].iloc[0]
    assert (t035["held_first"], t035["held_second"]) == (1, 0)


def test_campaign_settings_predict_the_corner_alike_on_both_runs(fits):
    """Both runs within 10 % of each other and 15 % of the computed ζ at CORNER (measured: 1.419e-3 and
    1.355e-3, 0.1 % and 4.6 % off), t035's weight there below 0.3 in magnitude, the scatter in the
    nugget (measured ν = 0.03-0.04, θ₁ = 0.3)."""
    (m1, z1, w1), (m2, z2, w2) = fits["first", "campaign"], fits["second", "campaign"]
    assert abs(z1 - z2) < 0.10 * ZETA_COMPUTED
    assert abs(z1 - ZETA_COMPUTED) < 0.15 * ZETA_COMPUTED and abs(z2 - ZETA_COMPUTED) < 0.15 * ZETA_COMPUTED
    assert max(abs(w1), abs(w2)) < 0.3
    assert min(m1.nugget, m2.nugget) > 1e-3


def test_library_defaults_show_the_fragility(fits):
    """The oracle above can fail: with θ ≥ 0.1 and no nugget θ₁ sits on its floor, t035 weighs about
    -1.2 at CORNER and the runs predict 1.16e-3 and 2.34e-3 there."""
    (m1, z1, w1), (m2, z2, w2) = fits["first", "library"], fits["second", "library"]
    assert m1.scale[0] == pytest.approx(0.1) and m2.scale[0] == pytest.approx(0.1)
    assert min(w1, w2) < -1.0
    assert abs(z1 - z2) > 0.5 * ZETA_COMPUTED
