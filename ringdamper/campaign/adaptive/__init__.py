"""The adaptive design of experiments: the training rings are chosen round by round where the Kriging
surrogates are unsure or the optimum may lie, and the campaign stops when the answer is settled.

Modules, one job each (method and its reasons: docs/adaptive.md):

- :mod:`.design`: the initial space-filling design (seeded by the reference rings), the per-round
  candidate sets, the gids of the rounds' rings and the campaign's sample table;
- :mod:`.model`: the surrogates a round fits on its training rings, their predictive mean and
  standard deviation;
- :mod:`.accuracy`: the estimates of the surrogates' validation error from training-side evidence;
- :mod:`.acquisition`: the exploration (predictive uncertainty) and exploitation (expected improvement
  of the optimum criterion) scores of the candidates;
- :mod:`.batch`: the distance rule that spreads a batch;
- :mod:`.stopping`: the stop decision from the estimated error, the optimum's stability and the budget;
- :mod:`.rounds`: one round (fit, predicted optimum, stop or choose) and its record, and the whole loop
  on any evaluation function (the tests' analytic ones);
- :mod:`.replay`: the rounds of a recorded campaign replayed on its rings, each judged on the
  validation rings (the stop rule's tests).
"""
