# Helpers shared by the rules.
import csv


def geometry_ids():
    """Every gid of samples.csv (the sampling checkpoint must have run)."""
    path = checkpoints.samples.get().output[0]
    with open(path) as fh:
        return [row["gid"] for row in csv.DictReader(fh)]
