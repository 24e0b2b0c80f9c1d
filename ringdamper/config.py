"""Load and validate the campaign configuration (docs/design.md §5).

Validation happens before any job runs: the JSON schema of ``workflow/schemas/`` (types, ranges,
closed objects), then the cross-field rules a schema cannot express (the ring must fit under the rim
overhang, the blade root must lie above the groove, ...). Every failure is one
:class:`ConfigError` whose message names the field, the value and the allowed range.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import yaml

REPO = Path(__file__).resolve().parent.parent
SCHEMA = REPO / "workflow" / "schemas" / "config.schema.yaml"
DEFAULT_CONFIG = REPO / "config.yaml"


class ConfigError(ValueError):
    """A configuration value is invalid; the message names the field and the allowed range."""


def _field_name(path) -> str:
    name = ""
    for part in path:
        name += f"[{part}]" if isinstance(part, int) else (f".{part}" if name else str(part))
    return name or "<config>"


def _describe(error) -> str:
    """One sentence for a jsonschema error: field, value, allowed range."""
    field = _field_name(error.absolute_path)
    schema = error.schema
    value = error.instance
    kind = error.validator
    if kind == "additionalProperties":
        allowed = sorted(schema.get("properties", {}))
        extra = sorted(set(value) - set(allowed)) if isinstance(value, dict) else []
        return f"{field}: unknown key(s) {extra}; allowed keys are {allowed}"
    if kind == "required":
        return f"{field}: {error.message}"
    if kind in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        lo = schema.get("minimum", schema.get("exclusiveMinimum"))
        hi = schema.get("maximum", schema.get("exclusiveMaximum"))
        lo_b = "[" if "minimum" in schema else "("
        hi_b = "]" if "maximum" in schema else ")"
        rng = f"{lo_b}{'-inf' if lo is None else lo}, {'+inf' if hi is None else hi}{hi_b}"
        return f"{field} = {value!r} is out of range: allowed {rng}"
    if kind == "type":
        return f"{field} = {value!r} has the wrong type: expected {schema.get('type')}"
    if kind == "enum":
        return f"{field} = {value!r} is not allowed: choose one of {schema['enum']}"
    return f"{field}: {error.message}"


def _schema_errors(config: dict) -> list[str]:
    import jsonschema

    schema = yaml.safe_load(SCHEMA.read_text())
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(config), key=lambda e: list(map(str, e.absolute_path)))
    return [_describe(e) for e in errors]


def _geometry_errors(config: dict) -> list[str]:
    """Cross-field rules of the sector geometry (docs/design.md §2)."""
    g = config["geometry"]
    blade, disk, ring = g["blade"], g["disk"], g["ring"]
    errors = []
    root = blade["tip_radius"] - blade["height"]
    lo_k1 = g["shape"]["kappa1_offsets"]
    if not disk["bore_radius"] < disk["contact_radius"] - ring["thickness"]:
        errors.append(
            f"geometry.disk.bore_radius = {disk['bore_radius']} must be below the ring's lower surface "
            f"(contact_radius - ring.thickness = {disk['contact_radius'] - ring['thickness']})")
    if not root > disk["contact_radius"] + max(lo_k1):
        errors.append(
            f"geometry.blade: root radius tip_radius - height = {root:.6g} must exceed "
            f"contact_radius + max(kappa1_offsets) = {disk['contact_radius'] + max(lo_k1):.6g}")
    errors += _ring_under_arm(g, disk["arm_length"], ring["axial_center"], "geometry.ring.axial_center")
    if not disk["arm_thickness"] > max(lo_k1):
        errors.append(f"geometry.disk.arm_thickness = {disk['arm_thickness']} must exceed the deepest "
                      f"groove, max(kappa1_offsets) = {max(lo_k1)}")
    if not disk["web_thickness"] < disk["rim_axial_width"]:
        errors.append(f"geometry.disk.web_thickness = {disk['web_thickness']} must be below "
                      f"rim_axial_width = {disk['rim_axial_width']}")
    if not blade["chord"] <= disk["rim_axial_width"] + 1e-12:
        errors.append(f"geometry.blade.chord = {blade['chord']} must not exceed "
                      f"geometry.disk.rim_axial_width = {disk['rim_axial_width']}")
    for i in (1, 2, 3):
        off = g["shape"][f"kappa{i}_offsets"]
        if not (off[0] <= 0.0 == off[1] <= off[2]):
            errors.append(f"geometry.shape.kappa{i}_offsets = {off} must be [<=0, 0, >=0]")
    thinnest = ring["thickness"] + min(lo_k1) - max(g["shape"]["kappa2_offsets"][2],
                                                    g["shape"]["kappa3_offsets"][2])
    if thinnest <= 0:
        errors.append(f"geometry.shape: the ring would have a non-positive thickness ({thinnest:.3g} m)")
    return errors


def ring_axial_center(geometry: dict, arm_length: float) -> float:
    """Axial centre (m) of the ring on an arm of length ``arm_length``: the ring moves with the arm's
    centre, keeping the configured ring's offset from it (a centred ring stays centred)."""
    disk = geometry["disk"]
    return geometry["ring"]["axial_center"] + (arm_length - disk["arm_length"]) / 2


def _ring_under_arm(geometry: dict, arm_length: float, center: float, field: str) -> list[str]:
    """The ring's axial band must lie under the arm (rim face + arm_length), not under the rim."""
    half_rim, width = geometry["disk"]["rim_axial_width"] / 2, geometry["ring"]["width"]
    lo, hi = half_rim + width / 2, half_rim + arm_length - width / 2
    if lo < center < hi:
        return []
    return [f"{field} = {center:.6g} must lie in ({lo:.6g}, {hi:.6g}) so that the ring sits under the "
            f"rim's arm (arm_length = {arm_length:.6g})"]


def _contact_state_errors(config: dict) -> list[str]:
    """The groove-support variants of ``studies.contact_state`` must be valid geometries: each arm
    thickness between the deepest groove and the blade root (the rim lies above the arm), each arm
    length long enough to carry the ring moved with it (:func:`ring_axial_center`)."""
    grid = config.get("studies", {}).get("contact_state")
    if grid is None:
        return []
    g = config["geometry"]
    deepest = max(g["shape"]["kappa1_offsets"])
    rim_depth = g["blade"]["tip_radius"] - g["blade"]["height"] - g["disk"]["contact_radius"]
    errors = [f"studies.contact_state.arm_thickness[{i}] = {t} must lie in ({deepest:.6g}, {rim_depth:.6g}): "
              "above the deepest groove (max kappa1_offsets), below the blade root"
              for i, t in enumerate(grid["arm_thickness"]) if not deepest < t < rim_depth]
    for i, length in enumerate(grid["arm_length"]):
        errors += _ring_under_arm(g, length, ring_axial_center(g, length),
                                  f"studies.contact_state.arm_length[{i}] = {length}: ring axial_center")
    return errors


def _solver_errors(config: dict) -> list[str]:
    """Cross-field rules of the solver sections."""
    errors = []
    d = config["dnnm"]
    if not d["amplitude_max"] > d["amplitude_min"]:
        errors.append(f"dnnm.amplitude_max = {d['amplitude_max']} must exceed "
                      f"dnnm.amplitude_min = {d['amplitude_min']}")
    if d["n_harmonics"] > config["reduction"]["n_harmonics"]:
        errors.append(f"dnnm.n_harmonics = {d['n_harmonics']} must not exceed "
                      f"reduction.n_harmonics = {config['reduction']['n_harmonics']}")
    top = d.get("max_harmonics", d["n_harmonics"])
    if not d["n_harmonics"] <= top <= config["reduction"]["n_harmonics"]:
        errors.append(f"dnnm.max_harmonics = {top} must lie in [dnnm.n_harmonics, reduction.n_harmonics] = "
                      f"[{d['n_harmonics']}, {config['reduction']['n_harmonics']}]")
    if d["n_time_samples"] < 2 * d["n_harmonics"] + 1:
        errors.append(f"dnnm.n_time_samples = {d['n_time_samples']} must be at least "
                      f"2 n_harmonics + 1 = {2 * d['n_harmonics'] + 1} (sampling theorem)")
    f = config["frf"]
    lo, hi = f["frequency_band"]
    if not lo < 1.0 < hi:
        errors.append(f"frf.frequency_band = {f['frequency_band']} must bracket 1 (the E-EBM resonance)")
    targets = f["target_amplitudes"]
    if any(b <= a for a, b in zip(targets, targets[1:])):
        errors.append(f"frf.target_amplitudes = {targets} must be strictly increasing")
    return errors


def _design_errors(s: dict, min_training: int) -> list[str]:
    """The design must give the Kriging fit its minimum training set: the paper design's training
    geometries, or the adaptive design's initial ones (the first round fits on them alone); the
    adaptive budget must cover the initial design."""
    if s.get("design", "paper") == "paper":
        n_training = len(s["factorial_levels"]) ** 3 + s["n_lhs_training"]
        if min_training > n_training:
            return [f"surrogate.min_training = {min_training} exceeds the {n_training} training geometries "
                    "of sampling"]
        return []
    a = s.get("adaptive")
    if a is None:
        return ["sampling.adaptive: required when sampling.design = 'adaptive'"]
    errors = []
    if a["n_initial"] < min_training:
        errors.append(f"sampling.adaptive.n_initial = {a['n_initial']} is below surrogate.min_training = "
                      f"{min_training}, the fewest training geometries the Kriging fit takes: allowed "
                      f"[{min_training}, +inf)")
    if a["n_max"] < a["n_initial"]:
        errors.append(f"sampling.adaptive.n_max = {a['n_max']} is below sampling.adaptive.n_initial = "
                      f"{a['n_initial']}: allowed [{a['n_initial']}, +inf)")
    return errors


def _analytics_errors(config: dict) -> list[str]:
    """Cross-field rules of the surrogate, exploration and sensitivity sections."""
    errors = []
    errors += _design_errors(config["sampling"], config["surrogate"]["min_training"])
    for i, (lo, hi) in enumerate(config["sensitivity"]["local_box"]):
        if not lo < hi:
            errors.append(f"sensitivity.local_box[{i}] = {[lo, hi]} must have low < high (kappa{i + 1})")
    levels = config["sensitivity"]["levels"]
    if any(b <= a for a, b in zip(levels, levels[1:])):
        errors.append(f"sensitivity.levels = {levels} must be strictly increasing")
    degree, n_pce = config["sensitivity"]["pce_degree"], config["sensitivity"]["pce_samples"]
    basis = math.comb(degree + 3, 3)  # polynomials of total degree <= p in the 3 shape parameters
    if n_pce < basis:
        errors.append(f"sensitivity.pce_samples = {n_pce} must be at least the {basis} polynomials of "
                      f"degree <= sensitivity.pce_degree = {degree}")
    return errors


def _imported_errors(config: dict) -> list[str]:
    """``geometry.source = imported`` needs the ``imported`` section; its directions must not vanish."""
    if config["geometry"].get("source", "builtin") != "imported":
        return []
    imported = config.get("imported")
    if imported is None:
        return ["imported: required when geometry.source = 'imported' (docs/imported.md)"]
    return [f"imported.{key} = {imported[key]} must not be the zero vector"
            for key in ("axis", "forcing_direction") if key in imported and not any(imported[key])]


def resolve_imported_mesh(config: dict, config_dir) -> dict:
    """``imported.mesh`` made absolute against the configuration file's folder (in place); a file that
    does not exist is a :class:`ConfigError` naming both paths."""
    imported = config.get("imported")
    if imported is None or config["geometry"].get("source", "builtin") != "imported":
        return config
    path = Path(imported["mesh"])
    resolved = path if path.is_absolute() else (Path(config_dir) / path).resolve()
    if not resolved.is_file():
        raise ConfigError(f"invalid configuration:\n  - imported.mesh = '{imported['mesh']}': no such file "
                          f"({resolved}; a relative path is read from the configuration file's folder {config_dir})")
    imported["mesh"] = str(resolved)
    return config


#: ``mesh.contact_pairs`` when the config has none: one pair on every node of the ring's upper surface.
NODE_PAIRS = {"placement": "nodes"}


def contact_pairs_setting(config: dict) -> dict:
    """``mesh.contact_pairs`` of ``config``, :data:`NODE_PAIRS` when absent."""
    return config["mesh"].get("contact_pairs", NODE_PAIRS)


def _contact_pairs_errors(config: dict) -> list[str]:
    """``mesh.contact_pairs``: the grid needs its two cell counts, the node placement takes none."""
    pairs = contact_pairs_setting(config)
    counts = [key for key in ("n_theta", "n_axial") if key in pairs]
    if pairs["placement"] == "grid" and len(counts) < 2:
        return ["mesh.contact_pairs: placement 'grid' needs n_theta and n_axial (cells in theta over the "
                "sector and across the ring's axial band, each >= 1)"]
    if pairs["placement"] == "nodes" and counts:
        return [f"mesh.contact_pairs.{counts[0]}: only for placement 'grid' (placement 'nodes' puts one pair "
                "on every node of the ring's upper surface)"]
    return []


def validate_config(config: dict[str, Any]) -> dict[str, Any]:
    """Validate ``config`` in place semantics; raise one :class:`ConfigError` listing every problem."""
    errors = _schema_errors(config)
    if not errors:
        errors = (_geometry_errors(config) + _solver_errors(config) + _analytics_errors(config)
                  + _contact_state_errors(config) + _imported_errors(config) + _contact_pairs_errors(config))
    if errors:
        raise ConfigError("invalid configuration:\n  - " + "\n  - ".join(errors))
    return config


def load_config(path: str | Path = DEFAULT_CONFIG) -> dict[str, Any]:
    """Read a YAML configuration and validate it."""
    with open(path) as fh:
        config = yaml.safe_load(fh)
    if not isinstance(config, dict):
        raise ConfigError(f"{path}: the configuration must be a YAML mapping")
    return resolve_imported_mesh(validate_config(config), Path(path).resolve().parent)
