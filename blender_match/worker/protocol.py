"""The line protocol between Blender (``client.WorkerJob``) and the worker process.

One JSON object per line, UTF-8, ``\\n``-terminated. Standard library only: Blender imports this.

Blender -> worker (the worker's stdin): one request line, then optionally a cancel line::

    {"type": "match", "photo": PATH, "out_dir": PATH, "options": {MatchOptions fields}}
    {"type": "render", "params_file": PATH, "out_dir": PATH, "size": N, "device": "auto", "overwrite": false}
    {"type": "probe"}
    {"type": "cancel"}

Closing the worker's stdin (the parent died) means cancel too.

Worker -> Blender (a dedicated protocol stream; anything else the worker or its libraries print
goes to stderr): any number of progress lines, then exactly one of result, error or cancelled::

    {"type": "progress", "stage": ..., "fraction": 0.4, "eta_seconds": 12.0, ...}
    {"type": "result", "report": {...}}
    {"type": "error", "message": "one line", "kind": "user" | "dependency" | "crash"}
    {"type": "cancelled"}

``decode`` raises ``ProtocolError`` on anything malformed; ``encode`` produces strict JSON (NaN
and infinities become null; numbers from numpy/torch scalars are converted).
"""
from __future__ import annotations

import json
import math
from typing import Any

from ..errors import BlenderMatchError

PROTOCOL_VERSION = 1
MAX_LINE_BYTES = 8 << 20

REQUEST_TYPES = ("match", "render", "probe")
CONTROL_TYPES = ("cancel",)
EVENT_TYPES = ("progress", "result", "error", "cancelled")
TERMINAL_TYPES = ("result", "error", "cancelled")
ERROR_KINDS = ("user", "dependency", "crash")


class ProtocolError(BlenderMatchError):
    """A line that is not a valid protocol message."""


# --- encoding ------------------------------------------------------------------------------------


def _plain(value: Any) -> Any:
    """``value`` as plain JSON data: non-finite floats -> None, scalars with ``item()`` (numpy,
    torch) -> Python numbers, paths and other objects -> str, tuples -> lists."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    item = getattr(value, "item", None)
    if callable(item):
        try:
            return _plain(item())
        except (TypeError, ValueError, RuntimeError):
            pass
    return str(value)


def one_line(text: str, limit: int = 2000) -> str:
    """``text`` collapsed to one line (whitespace runs become one space), at most ``limit`` chars."""
    line = " ".join(str(text).split())
    return line if len(line) <= limit else line[: limit - 1] + "…"


def encode(message: dict) -> bytes:
    """One protocol line (bytes, ending in a newline). Validates the message first."""
    message = _plain(message)
    validate(message)
    return (json.dumps(message, ensure_ascii=False, allow_nan=False, separators=(",", ":")) + "\n").encode("utf-8")


def decode(line: bytes | str) -> dict:
    """The message on one line (ProtocolError if it is not valid JSON or not a valid message)."""
    if isinstance(line, bytes):
        if len(line) > MAX_LINE_BYTES:
            raise ProtocolError(f"line too long ({len(line)} bytes)")
        try:
            line = line.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise ProtocolError(f"not UTF-8: {exc}") from None
    text = line.strip()
    if not text:
        raise ProtocolError("empty line")
    if len(text) > MAX_LINE_BYTES:
        raise ProtocolError(f"line too long ({len(text)} characters)")
    try:
        message = json.loads(text, parse_constant=_reject_constant)
    except json.JSONDecodeError as exc:
        raise ProtocolError(f"not JSON: {exc.msg} at column {exc.colno}: {one_line(text, 80)!r}") from None
    validate(message)
    return message


def _reject_constant(name: str):
    raise ProtocolError(f"not strict JSON: {name}")


# --- validation ----------------------------------------------------------------------------------


def _field(message: dict, key: str, types, what: str, optional: bool = False):
    if key not in message:
        if optional:
            return
        raise ProtocolError(f"{message['type']}: missing {key!r}")
    value = message[key]
    if value is None and optional:
        return
    if isinstance(value, bool) and bool not in (types if isinstance(types, tuple) else (types,)):
        raise ProtocolError(f"{message['type']}: {key!r} must be {what}, got {value!r}")
    if not isinstance(value, types):
        raise ProtocolError(f"{message['type']}: {key!r} must be {what}, got {type(value).__name__}")


def validate(message: Any) -> None:
    """ProtocolError unless ``message`` is a well-formed request, control or event message."""
    if not isinstance(message, dict):
        raise ProtocolError(f"a message must be a JSON object, got {type(message).__name__}")
    kind = message.get("type")
    if not isinstance(kind, str):
        raise ProtocolError("a message needs a string 'type'")
    number = (int, float)
    if kind == "match":
        _field(message, "photo", str, "a path")
        _field(message, "out_dir", str, "a path")
        _field(message, "options", dict, "an object", optional=True)
    elif kind == "render":
        _field(message, "params_file", str, "a path")
        _field(message, "out_dir", str, "a path")
        _field(message, "size", int, "an integer")
        _field(message, "device", str, "a string", optional=True)
        _field(message, "overwrite", bool, "true or false", optional=True)
    elif kind in ("probe", "cancel", "cancelled"):
        pass
    elif kind == "progress":
        _field(message, "stage", str, "a string")
        _field(message, "fraction", number, "a number", optional=True)
        _field(message, "eta_seconds", number, "a number or null", optional=True)
        fraction = message.get("fraction")
        if fraction is not None and not -1e-6 <= fraction <= 1 + 1e-6:
            raise ProtocolError(f"progress: 'fraction' must be in [0, 1], got {fraction}")
    elif kind == "result":
        _field(message, "report", dict, "an object")
    elif kind == "error":
        _field(message, "message", str, "a string")
        _field(message, "kind", str, "a string")
        if message["kind"] not in ERROR_KINDS:
            raise ProtocolError(f"error: 'kind' must be one of {', '.join(ERROR_KINDS)}, got {message['kind']!r}")
        if "\n" in message["message"]:
            raise ProtocolError("error: 'message' must be one line")
    else:
        known = REQUEST_TYPES + CONTROL_TYPES + EVENT_TYPES
        raise ProtocolError(f"unknown message type {kind!r} (expected one of {', '.join(known)})")


def is_request(message: dict) -> bool:
    return message.get("type") in REQUEST_TYPES


def is_terminal(message: dict) -> bool:
    return message.get("type") in TERMINAL_TYPES


# --- constructors --------------------------------------------------------------------------------


def match_request(photo, out_dir, options: dict | None = None) -> dict:
    """A match request; ``options`` holds MatchOptions fields (graph, size, quality, seed, device,
    overwrite, iterations)."""
    return {"type": "match", "photo": str(photo), "out_dir": str(out_dir), "options": dict(options or {})}


def render_request(params_file, out_dir, size: int, device: str = "auto", overwrite: bool = False) -> dict:
    return {"type": "render", "params_file": str(params_file), "out_dir": str(out_dir), "size": int(size),
            "device": device, "overwrite": bool(overwrite)}


def probe_request() -> dict:
    return {"type": "probe"}


def cancel_message() -> dict:
    return {"type": "cancel"}


def progress_event(event: dict) -> dict:
    return {**event, "type": "progress"}


def result_event(report: dict) -> dict:
    return {"type": "result", "report": report}


def error_event(message: str, kind: str) -> dict:
    return {"type": "error", "message": one_line(message), "kind": kind}


def cancelled_event() -> dict:
    return {"type": "cancelled"}
