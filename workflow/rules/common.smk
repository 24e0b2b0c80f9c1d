# Shared by the rule files (what one rule file alone uses lives in that file). The design of
# experiments known before any job runs is seeded and deterministic, so it is computed at parse time:
# the paper design whole, the adaptive design's initial rings and the validation rings. The rings the
# adaptive rounds add are known only once each round's checkpoint has written its record
# (adaptive.smk); the functions below resolve them through the checkpoints.
import json

import yaml

from ringdamper.campaign.adaptive.design import round_of
from ringdamper.campaign.design_space import REFERENCE_RINGS
from ringdamper.campaign.sampling import make_samples
from ringdamper.logs import cpu_record

SAMPLES = make_samples(config["sampling"]).set_index("gid")
ADAPTIVE = config["sampling"].get("design", "paper") == "adaptive"


# The configuration sections each stage's outputs depend on: the stage's own, and through its input
# files those of every stage upstream. A rule passes them to its script as `params.config`, the only
# configuration the script reads, so Snakemake's params trigger reruns exactly the jobs downstream of
# an edited section, and every NetCDF file records their hash (ringdamper.io.provenance).
MODEL = ("material", "geometry", "mesh", "operation", "substructure")
STATIC = MODEL + ("contact", "static")
REDUCED = MODEL + ("reduction",)
MODAL = STATIC + ("modal",)
DNNM = STATIC + ("reduction", "modal", "dnnm")
FORCED = DNNM + ("frf",)
DATASET = ("sampling",) + DNNM
SURROGATE = DATASET + ("surrogate",)
EXPLORATION = SURROGATE + ("exploration",)
SENSITIVITY = SURROGATE + ("sensitivity",)


SUPERELEMENT = f"{RESULTS}/superelement/fixed_part.npz"


def superelement_input(wildcards):
    """The fixed part's super-element when ``substructure.enabled`` (docs/reduction.md), else none."""
    return [SUPERELEMENT] if config.get("substructure", {}).get("enabled", False) else []


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
    """The geometries known at parse time (the whole design of ``paper``)."""
    return list(SAMPLES.index)


def round_record(round_):
    """The record of adaptive round ``round_`` (checkpoint adaptive_round): chosen rings, stop decision."""
    return f"{RESULTS}/adaptive/round_{round_}.yaml"


def round_models(round_):
    """The models adaptive round ``round_`` fitted (a kriging.nc Dataset)."""
    return f"{RESULTS}/adaptive/round_{round_}_kriging.nc"


def stopping_round_models(wildcards):
    """The models of the round that stopped (none for the paper design): the rule kriging takes them when
    they were fitted on the campaign's training rings."""
    records = finished_rounds()
    return [round_models(records[-1]["round"])] if records else []


def read_round(round_):
    """The record of round ``round_``; raises until its checkpoint has run (Snakemake then runs it)."""
    with open(checkpoints.adaptive_round.get(round=str(round_)).output[0]) as fh:
        return yaml.safe_load(fh)


def rounds_before(round_):
    """The records of rounds 1 .. round_ - 1."""
    return [read_round(k) for k in range(1, round_)]


def finished_rounds():
    """The records of every round up to the one that stopped (none for the paper design)."""
    records = []
    while ADAPTIVE and not (records and records[-1]["stop"]):
        records.append(read_round(len(records) + 1))
    return records


def chosen_gids(records):
    return [c["gid"] for record in records for c in record["chosen"]]


def training_gids_before(round_):
    """The training rings round ``round_`` fits on: the initial design's and those earlier rounds chose."""
    return list(SAMPLES.index[SAMPLES.split == "training"]) + chosen_gids(rounds_before(round_))


def round_training(wildcards):
    """The training rings of the round of ``wildcards.round``."""
    return training_gids_before(int(wildcards.round))


def campaign_gids():
    """Every geometry of the campaign: the parse-time table and the rings of every round."""
    return geometry_ids() + chosen_gids(finished_rounds())


def campaign_files(name):
    """Input function: results/geometry/<gid>/``name`` of every geometry of the campaign."""
    return lambda wildcards: [f"{RESULTS}/geometry/{gid}/{name}" for gid in campaign_gids()]


# The design-comparison table of the report (adaptive_report): the other design's row is read from
# docs/adaptive/ when committed.
DESIGN_ROW = "docs/adaptive/{design}_design_row.csv"
OTHER_DESIGN = {"adaptive": "paper", "paper": "adaptive"}[config["sampling"].get("design", "paper")]


def chain_jobs():
    """The names of every job the design's training and validation rings and rounds cost."""
    jobs = [f"{stage}/{gid}" for gid in campaign_gids() for stage in ("static", "reduced", "dnnm")]
    return jobs + [f"adaptive/round_{r['round']}" for r in finished_rounds()]


def chain_benchmarks(wildcards):
    """The benchmark files (wall time) of :func:`chain_jobs`."""
    return [benchmark_file(name) for name in chain_jobs()]


def chain_cpu_records(wildcards):
    """The CPU-time records (ringdamper.logs.cpu_record) of :func:`chain_jobs`, in the same order."""
    return [str(cpu_record(log_file(name))) for name in chain_jobs()]


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
    """Input fixing kappa: none for a sampled geometry, optimum.yaml for gid ``optimum``, the round's
    record for a ring an adaptive round chose."""
    if wildcards.gid == OPTIMUM_GID:
        return [optimum_yaml()]
    round_ = round_of(wildcards.gid)
    return [checkpoints.adaptive_round.get(round=str(round_)).output[0]] if round_ else []


def kappa_of(wildcards):
    """kappa of geometry ``gid`` (the sample table, optimum.yaml for gid ``optimum``, or the record of
    the round that chose it)."""
    if wildcards.gid == OPTIMUM_GID:
        with open(optimum_yaml()) as fh:
            return [float(k) for k in yaml.safe_load(fh)["kappa"]]
    round_ = round_of(wildcards.gid)
    if round_:
        chosen = {c["gid"]: c["kappa"] for c in read_round(round_)["chosen"]}
        return [float(k) for k in chosen[wildcards.gid]]
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


# A geometry's chain is one cluster job (group geometry_<gid>) when its kappa is known when the DAG is
# first built. The rings a checkpoint adds (the optimum, an adaptive round's) run ungrouped: Snakemake
# 9 replaces their jobs when it re-evaluates the DAG after the checkpoint and does not re-register the
# new jobs' group, so a grouped one can crash the scheduler (KeyError in DAG.update_ready; upstream
# snakemake issue 4202).
def chain_group(wildcards):
    """Cluster job group of geometry ``gid``'s static -> reduced -> dnnm chain, or None."""
    if wildcards.gid == OPTIMUM_GID or round_of(wildcards.gid) is not None:
        return None
    return f"geometry_{wildcards.gid}"


def frf_curves(gid):
    """Forced-response curves of geometry ``gid``, one per forcing level (1, 2, ...)."""
    levels = range(1, len(config["frf"]["target_amplitudes"]) + 1)
    return [f"{RESULTS}/frf/{gid}/gamma_{level}.nc" for level in levels]
