"""Where the methods fail (docs/method_limits.md), each limit measured on systems with a known
answer: the E-EBM against the forced response as damping grows (:mod:`.eebm_validity`), H = 1
against converged harmonics when contacts separate (:mod:`.harmonics`), the Kriging predictive σ
against the true error with few points and near the boundary (:mod:`.kriging_coverage`), and
Hill's stability of forced responses (:mod:`.stability`); charts in :mod:`.figures`."""
from __future__ import annotations


def run(study: str, png, dataset=None, sizes=(20, 40, 60, 100), surrogate: dict | None = None):
    """Run ``study`` (``eebm_validity``, ``harmonics``, ``stability`` or ``kriging_coverage``, the
    last on the campaign ``dataset`` with training ``sizes`` and the ``surrogate`` settings), draw
    its chart to ``png`` and return its dataset."""
    from ringdamper.campaign.dataset import usable_mask

    from . import eebm_validity, figures, harmonics, kriging_coverage, stability

    if study == "eebm_validity":
        ds = eebm_validity.validity_study()
        ds.attrs.update({f"limit_{f}": eebm_validity.limit(ds, f) for f in dict.fromkeys(ds.family.values)})
        figures.plot_eebm_validity(ds, png)
    elif study == "harmonics":
        ds = harmonics.truncation_study()
        ds.attrs["indicator_limit_1pct"] = harmonics.indicator_limit(ds)
        figures.plot_harmonics(ds, png)
    elif study == "stability":
        ds = stability.stability_study()
        figures.plot_stability(ds, png)
    elif study == "kriging_coverage":
        if dataset is None:
            raise ValueError("kriging_coverage needs the campaign dataset")
        ds = kriging_coverage.coverage_study(dataset, usable_mask(dataset), sizes, surrogate)
        figures.plot_kriging_coverage(ds, png)
    else:
        raise ValueError(f"study {study!r}; allowed eebm_validity, harmonics, stability, kriging_coverage")
    return ds
