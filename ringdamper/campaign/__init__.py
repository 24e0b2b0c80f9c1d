"""Campaign-level stages: sampling, aggregation, surrogates, exploration, sensitivity."""
