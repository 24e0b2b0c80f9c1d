"""Ordinary Kriging surrogates of the dNNM outputs, one per (output, modal amplitude) (paper §3.2).

Modules:

- :mod:`.gp`: the Gaussian-process model in numpy: correlation kernels, predictor and variance,
  leave-one-out residuals, Q² and the leave-one-out variance calibration;
- :mod:`.settings`: the ``surrogate`` settings (kernel, multistart, scale bounds, nugget), defaults
  and validation;
- :mod:`.fit`: the maximum-likelihood fit of one model with OpenTURNS, checked against OpenTURNS'
  own predictor;
- :mod:`.campaign`: every model of a campaign dataset, on a process pool → the ``kriging.nc`` Dataset;
- :mod:`.surrogate`: the models of a ``kriging.nc`` rebuilt for vectorised prediction.

Method, settings, the ``kriging.nc`` layout and the measurements behind the choices: docs/surrogate.md.
"""

from .campaign import (
    OUTPUTS,
    PARAMETERS,
    STATUS_CONSTANT,
    STATUS_GP,
    STATUS_MEANINGS,
    STATUS_UNFITTED,
    fit_campaign,
    fitted_on,
)
from .fit import AMPLITUDE_RTOL, CONSTANT_RTOL, MATCH_RTOL, NUGGET_PROFILE, fit_model, fit_ot
from .gp import BAND_PROBABILITY, KERNELS, SIGMA_BAND, GPModel, correlation, q2
from .settings import DEFAULT_SETTINGS, DOMAIN_WIDTH, check_settings
from .surrogate import KrigingSurrogate, predict

__all__ = ["AMPLITUDE_RTOL", "BAND_PROBABILITY", "CONSTANT_RTOL", "DEFAULT_SETTINGS", "DOMAIN_WIDTH", "KERNELS",
           "MATCH_RTOL", "NUGGET_PROFILE", "OUTPUTS", "PARAMETERS", "SIGMA_BAND", "STATUS_CONSTANT", "STATUS_GP",
           "STATUS_MEANINGS", "STATUS_UNFITTED", "GPModel", "KrigingSurrogate", "check_settings", "correlation",
           "fit_campaign", "fit_model", "fit_ot", "fitted_on", "predict", "q2"]
