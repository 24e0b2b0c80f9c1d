"""The one-at-a-time cases of the fidelity study.

Each dial (an entry of ``fidelity.dials``: name, configuration key ``section.key`` and a list of
values) changes one key; a case is (ring, dial, value) and changes only that key of the campaign
configuration. The finest value of a dial (last in its list) is that dial's converged reference: the error of a case is
measured against the case of the same ring and dial at the finest value, every other key at its
default, so that each dial's error is its own. A dial runs on the rings of its ``rings`` list (all
rings when absent); the case of a dial at its default value is the one case ``(ring, "default",
"default")`` shared by every dial.
"""

from __future__ import annotations

import copy

DEFAULT = "default"


def rings(fidelity: dict) -> dict:
    """Ring name -> kappa."""
    return {r["name"]: r["kappa"] for r in fidelity["rings"]}


def dials(fidelity: dict) -> dict:
    """Dial name -> its entry (key, values, optional rings), in the configuration's order."""
    return {d["name"]: d for d in fidelity["dials"]}


def case_key(config: dict, ring: str, dial: str, label: str) -> tuple[str, str, str]:
    """(ring, dial, value) of a case, the shared default case when ``label`` is the dial's default."""
    if label == value_label(default_value(config, dial)):
        return ring, DEFAULT, DEFAULT
    return ring, dial, label


def dial_rings(fidelity: dict, dial: str) -> list[str]:
    """The rings dial ``dial`` runs on."""
    return list(dials(fidelity)[dial].get("rings", rings(fidelity)))


def dial_cases(config: dict) -> list[tuple[str, str, str]]:
    """All distinct (ring, dial, value) cases, values as strings (Snakemake wildcards)."""
    fid = config["fidelity"]
    keys = [case_key(config, ring, dial, value_label(v)) for dial, spec in dials(fid).items()
            for ring in dial_rings(fid, dial) for v in spec["values"]]
    return list(dict.fromkeys(keys))


def value_label(value) -> str:
    """Wildcard text of a dial value: integers as such, floats in repr (1e-08)."""
    return str(int(value)) if float(value).is_integer() and abs(value) >= 1 else repr(float(value))


def parse_value(spec: dict, label: str):
    """The dial value of a wildcard, checked against the dial's list."""
    for v in spec["values"]:
        if value_label(v) == label:
            return v
    raise ValueError(f"fidelity dial {spec['key']}: value {label} is not one of {spec['values']}")


def case_config(config: dict, dial: str, label: str) -> dict:
    """Copy of ``config`` with dial ``dial`` set to the value ``label``. The reduction keeps at least
    the harmonics the dNNM asks for (reduction.n_harmonics >= dnnm.n_harmonics). A case of the dial
    ``dnnm.n_harmonics`` is at that H throughout (``dnnm.max_harmonics`` = H: no adaptive truncation)."""
    if dial == DEFAULT:
        return copy.deepcopy(config)
    known = dials(config["fidelity"])
    spec = known.get(dial)
    if spec is None:
        raise ValueError(f"fidelity.dials has no dial {dial!r}; known: {sorted(known)}")
    out = copy.deepcopy(config)
    section, key = spec["key"].split(".")
    if section not in out or key not in out[section]:
        raise ValueError(f"fidelity.dials.{dial}.key = {spec['key']!r} is not a configuration key")
    out[section][key] = parse_value(spec, label)
    if spec["key"] == "dnnm.n_harmonics":
        out["dnnm"]["max_harmonics"] = out["dnnm"]["n_harmonics"]
    red = out["reduction"]
    red["n_harmonics"] = max(red["n_harmonics"], out["dnnm"]["n_harmonics"])
    return out


def default_value(config: dict, dial: str):
    """The campaign's current setting of a dial."""
    section, key = dials(config["fidelity"])[dial]["key"].split(".")
    return config[section][key]
