"""A matched material's exposed parameters as sliders: the paper's material editing.

A material built from a match stores its fitted parameters (params.json's text) in its
``"blender_match"`` custom property. The graph's exposed parameters (``exposed.NAME`` entries)
are copied into ``material.blender_match_params`` (a collection of ``PG_parameter`` items, with
the ranges of the library graph's ``.json``) when the material is built; the panel draws them as
sliders, and "Apply" writes an edited params.json (the stored one with the sliders' values) for a
re-render. bpy-free apart from the collection it fills, so the JSON side is testable alone.
"""
from __future__ import annotations

import json

from ..errors import BlenderMatchError
from . import addon

PROPERTY = "blender_match"        # the material's custom property (material_builder.PROPERTY)
COLLECTION = "blender_match_params"  # the Material collection property of the sliders
PREFIX = "exposed."


class ParameterError(BlenderMatchError):
    """Stored parameters that cannot be edited (the message says why)."""


def stored_record(material) -> dict | None:
    """The material's ``"blender_match"`` property as a plain dict (None if it has none)."""
    if material is None:
        return None
    record = material.get(PROPERTY)
    if record is None:
        return None
    try:
        return record.to_dict() if hasattr(record, "to_dict") else dict(record)
    except (TypeError, ValueError):
        return None


def stored_params(material) -> dict:
    """The material's stored params.json, parsed (ParameterError when missing or unreadable)."""
    record = stored_record(material)
    if not record or not isinstance(record.get("params"), str):
        raise ParameterError(f"material {material.name if material else None!r} was not made by "
                             "Blender Match (no stored parameters)")
    try:
        data = json.loads(record["params"])
    except json.JSONDecodeError as exc:
        raise ParameterError(f"material {material.name!r}: its stored parameters are not JSON ({exc})") from None
    if not isinstance(data, dict) or not isinstance(data.get("params"), dict):
        raise ParameterError(f"material {material.name!r}: its stored parameters have no \"params\"")
    return data


def editable_parameters(data: dict) -> list[dict]:
    """The stored parameters the panel can edit: the ``exposed.NAME`` entries of a library graph,
    in the graph's order, with its ranges: dicts of name, kind ("FLOAT" or "COLOR"), value,
    minimum, maximum, default."""
    library = addon.graph_source_name(data.get("source")) or addon.graph_source_name(data.get("graph"))
    if library is None:
        return []
    entry = addon.library_graphs()[library]
    params = data["params"]
    found = []
    for name in entry["exposed"]:
        key = PREFIX + name
        spec = entry["exposed_params"].get(name) or {}
        value = params.get(key)
        if value is None:
            continue
        lo, hi = float(spec.get("min", 0.0)), float(spec.get("max", 1.0))
        if isinstance(value, list):
            if len(value) not in (3, 4) or not all(isinstance(v, (int, float)) for v in value):
                continue
            found.append({"name": name, "kind": "COLOR", "value": [float(v) for v in value[:3]],
                          "minimum": lo, "maximum": hi, "default": spec.get("default")})
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            found.append({"name": name, "kind": "FLOAT", "value": float(value), "minimum": lo, "maximum": hi,
                          "default": spec.get("default")})
    return found


def populate(material) -> int:
    """Fill ``material.blender_match_params`` from its stored parameters; how many there are."""
    items = getattr(material, COLLECTION)
    items.clear()
    try:
        data = stored_params(material)
    except ParameterError:
        return 0
    for param in editable_parameters(data):
        item = items.add()
        item.name = param["name"]
        item.kind = param["kind"]
        item.minimum, item.maximum = param["minimum"], param["maximum"]
        if param["kind"] == "COLOR":
            item.color = [min(max(v, 0.0), 1.0) for v in param["value"]]
        else:
            item.raw = min(max(param["value"], param["minimum"]), param["maximum"])
    return len(items)


def slider_values(material) -> dict:
    """``{"exposed.NAME": value}`` of the material's sliders."""
    values: dict[str, float | list[float]] = {}
    for item in getattr(material, COLLECTION):
        if item.kind == "COLOR":
            values[PREFIX + item.name] = [round(float(c), 6) for c in item.color]
        else:
            values[PREFIX + item.name] = round(float(item.raw), 6)
    return values


def edited_params(data: dict, values: dict) -> dict:
    """The stored parameter file ``data`` with ``values`` (``{"exposed.NAME": value}``) put in:
    the same format, a colour keeps any components beyond RGB (alpha) it had."""
    edited = json.loads(json.dumps(data))
    params = edited["params"]
    for key, value in values.items():
        if key not in params:
            raise ParameterError(f"the stored parameters have no {key!r}")
        old = params[key]
        if isinstance(old, list):
            value = list(value) + list(old[len(value):])
        params[key] = value
    return edited


def changed(data: dict, values: dict, tolerance: float = 1e-6) -> list[str]:
    """The keys of ``values`` that differ from the stored ``data``."""
    out = []
    for key, value in values.items():
        old = data["params"].get(key)
        old = old[:len(value)] if isinstance(old, list) and isinstance(value, list) else old
        a = value if isinstance(value, list) else [value]
        b = old if isinstance(old, list) else [old]
        if len(a) != len(b) or any(x is None or y is None or abs(x - y) > tolerance for x, y in zip(a, b)):
            out.append(key)
    return out
