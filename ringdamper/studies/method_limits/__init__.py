"""Where the methods fail (docs/method_limits.md), each limit measured on systems with a known
answer: the E-EBM against the forced response as damping grows (:mod:`.eebm_validity`), H = 1
against converged harmonics when contacts separate (:mod:`.harmonics`), the Kriging predictive σ
against the true error with few points and near the boundary (:mod:`.kriging_coverage`), and
Hill's stability of forced responses (:mod:`.stability`). :func:`run` gives a study's dataset;
its chart is drawn from that dataset by the rule script."""
from __future__ import annotations

#: The studies :func:`run` knows.
STUDIES = ("eebm_validity", "harmonics", "stability", "kriging_coverage")


def run(study: str, dataset=None, sizes=(20, 40, 60, 100), surrogate: dict | None = None):
    """The dataset of ``study`` (``eebm_validity``, ``harmonics``, ``stability`` or
    ``kriging_coverage``, the last on the campaign ``dataset`` with training ``sizes`` and the
    ``surrogate`` settings)."""
    from ringdamper.campaign.dataset import usable_mask

    from . import eebm_validity, harmonics, kriging_coverage, stability

    if study == "eebm_validity":
        ds = eebm_validity.validity_study()
        ds.attrs.update({f"limit_{f}": eebm_validity.limit(ds, f) for f in dict.fromkeys(ds.family.values)})
    elif study == "harmonics":
        ds = harmonics.truncation_study()
        ds.attrs["indicator_limit_1pct"] = harmonics.indicator_limit(ds)
    elif study == "stability":
        ds = stability.stability_study()
    elif study == "kriging_coverage":
        if dataset is None:
            raise ValueError("kriging_coverage needs the campaign dataset")
        ds = kriging_coverage.coverage_study(dataset, usable_mask(dataset), sizes, surrogate)
    else:
        raise ValueError(f"study {study!r}; allowed {', '.join(STUDIES)}")
    return ds
