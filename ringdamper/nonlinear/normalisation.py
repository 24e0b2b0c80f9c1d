"""Normalised frequency of the paper's figures (docs/design.md §2, *Frequency normalisation*):
ω0 = 2.195 · ω / ω_stuck,default, with ω_stuck,default the default ring's linearised stuck
frequency at operating speed, so that figures compare directly with the paper's axes."""

PAPER_NORMALISED_FREQUENCY = 2.195


def normalised_frequency(frequency, reference):
    """``2.195 · frequency / reference`` (any consistent units: Hz/Hz or rad/s over rad/s)."""
    return PAPER_NORMALISED_FREQUENCY * frequency / reference
