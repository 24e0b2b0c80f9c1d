# Shared by the rule files (what one rule file alone uses lives in that file). The design of
# experiments is seeded and deterministic, so it is computed at parse time: the DAG is static and a dry
# run lists every job (the `samples` rule writes the same table).
import json

import yaml

from ringdamper.campaign.sampling import REFERENCE_RINGS, make_samples

SAMPLES = make_samples(config["sampling"]).set_index("gid")


# The configuration sections each stage's outputs depend on: the stage's own, and through its input
# files those of every stage upstream. A rule passes them to its script as `params.config`, the only
# configuration the script reads, so Snakemake's params trigger reruns exactly the jobs downstream of
# an edited section, and every NetCDF file records their hash (ringdamper.io.provenance).
MODEL = ("material", "geometry", "mesh", "operation")
STATIC = MODEL + ("contact", "static")
REDUCED = MODEL + ("reduction",)
MODAL = STATIC + ("modal",)
DNNM = STATIC + ("reduction", "modal", "dnnm")
FORCED = DNNM + ("frf",)
DATASET = ("sampling",) + DNNM
SURROGATE = DATASET + ("surrogate",)
EXPLORATION = SURROGATE + ("exploration",)
SENSITIVITY = SURROGATE + ("sensitivity",)


def sections(*names):
    """The configuration restricted to ``names`` (a rule's ``params.config``): whole sections, or one
    key of a section as ``section.key`` (a study whose jobs read only part of its section). A section
    the configuration lacks (the studies' in a user's campaign) is left out: its rules cannot run.
    Keys are sorted at every level, so that reordering a configuration file reruns nothing."""
    selected = {}
    for name in names:
        section, _, key = name.partition(".")
        if section not in config:
            continue
        if key:
            selected.setdefault(section, {})[key] = config[section][key]
        else:
            selected[section] = config[section]
    return json.loads(json.dumps(selected, sort_keys=True))


def log_file(name):
    """The log file of job ``name`` (may hold wildcards): results/logs/<name>.log."""
    return f"{RESULTS}/logs/{name}.log"


def benchmark_file(name):
    """The time and memory record of job ``name``: results/benchmarks/<name>.tsv."""
    return f"{RESULTS}/benchmarks/{name}.tsv"


def geometry_ids():
    return list(SAMPLES.index)


# Resources for a cluster (threads, mem_mb, runtime in minutes), declared in each rule from the
# benchmarks of the 120-geometry campaign on the default mesh (results/benchmarks/): mem_mb about
# twice the largest max_rss, runtime ten times the longest wall time and at least 5 min. A job
# killed for memory is retried (profiles/slurm: retries) with its request doubled at each attempt.
def scaled(mem_mb):
    """mem_mb of attempt 1, 2, ...: ``mem_mb`` times the attempt."""
    return lambda wildcards, attempt: mem_mb * attempt


# The optimum found on the surrogate is a real geometry: gid ``optimum``, whose kappa is only known
# once the checkpoint ``optimum`` has written optimum.yaml. Its static, reduced and dnnm jobs
# take that file as input (``kappa_source``), so Snakemake runs the checkpoint first and re-evaluates
# the DAG; ``checkpoints.optimum.get()`` raises until then.
OPTIMUM_GID = "optimum"


def optimum_yaml():
    return checkpoints.optimum.get().output[0]


def kappa_source(wildcards):
    """Input fixing kappa: none for a sampled geometry, optimum.yaml for gid ``optimum``."""
    return [optimum_yaml()] if wildcards.gid == OPTIMUM_GID else []


def kappa_of(wildcards):
    """kappa of geometry ``gid`` (the sample table, or optimum.yaml for gid ``optimum``)."""
    if wildcards.gid == OPTIMUM_GID:
        with open(optimum_yaml()) as fh:
            return [float(k) for k in yaml.safe_load(fh)["kappa"]]
    row = SAMPLES.loc[wildcards.gid]
    return [float(row.kappa1), float(row.kappa2), float(row.kappa3)]


def gid_of(kappa):
    """gid of the sample at exactly ``kappa`` (every reference ring is in the table)."""
    hit = SAMPLES[(SAMPLES[["kappa1", "kappa2", "kappa3"]] == list(kappa)).all(axis=1)]
    return hit.index[0]


# The default ring: its static state drives the modal stage, whose resonance and the default ring's
# stuck frequency (stuck_default) normalise every dnnm.nc. On a cluster its chain, the modal stage and
# stuck_default form one job (group geometry_<default gid>); every other geometry's chain is a job.
DEFAULT_GID = gid_of((0.0, 0.0, 0.0))


def reference_gids():
    """Every reference ring (label -> gid): default, one-at-a-time extremes, the paper's optimum."""
    return {label: gid_of(k) for label, k in REFERENCE_RINGS.items()}


def frf_curves(gid):
    """Forced-response curves of geometry ``gid``, one per forcing level (1, 2, ...)."""
    levels = range(1, len(config["frf"]["target_amplitudes"]) + 1)
    return [f"{RESULTS}/frf/{gid}/gamma_{level}.nc" for level in levels]
