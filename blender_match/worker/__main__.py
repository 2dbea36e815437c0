"""``python -m blender_match.worker``: run one job for Blender and report on a protocol stream.

Reads one request line from stdin (see ``protocol``), runs it (``pipeline.match_photo``,
``pipeline.render_params`` or ``probe``) and writes progress lines, then one result, error or
cancelled line. A background thread keeps reading stdin: a ``cancel`` line, or end of file (the
parent went away), sets the cancel flag the pipeline polls.

Protocol lines go to the process's original stdout only; before running anything the worker points
file descriptor 1 and ``sys.stdout`` at stderr, so stray prints and warnings from any library
(Python or C) land in stderr, which the client keeps as a log.

Outcomes: ``errors.Cancelled`` (or an interrupt after a cancel line) -> a cancelled line; missing
packages -> an error of kind ``dependency``; errors the user can fix (``errors.BlenderMatchError``,
``OSError``, out of memory) -> ``user``; anything else is a bug -> ``crash`` with a one-line
summary and the traceback on stderr.
"""
from __future__ import annotations

import importlib
import importlib.metadata
import importlib.util
import os
import platform
import sys
import threading
import time
import traceback
from pathlib import Path

from ..allocator import keep_freed_memory
from ..errors import BlenderMatchError, Cancelled
from ..version import __version__
from . import protocol
from .backend_setup import WORKER_IMPORTS

PROGRESS_INTERVAL = 0.1  # seconds: at most ~10 progress lines a second


class DependencyError(BlenderMatchError):
    """The worker's Python lacks a package the job needs."""


class Channel:
    """The protocol stream: thread-safe, throttled progress, silent once the reader is gone."""

    def __init__(self, fd: int):
        self._file = os.fdopen(fd, "wb", buffering=0)
        self._lock = threading.Lock()
        self._last_progress = 0.0
        self._last_stage = None
        self._held: dict | None = None
        self.broken = False

    def send(self, message: dict) -> None:
        try:
            line = protocol.encode(message)
        except protocol.ProtocolError as exc:
            print(f"blender_match.worker: not sent, invalid message ({exc}): {message!r}", file=sys.stderr)
            return
        with self._lock:
            if self.broken:
                return
            try:
                self._file.write(line)
            except (BrokenPipeError, OSError):
                self.broken = True

    def progress(self, event: dict) -> None:
        """The pipeline's progress callback: forwards at most one event per PROGRESS_INTERVAL,
        always the first of a new stage (preceded by the last one held back from the stage
        before, so that a stage's final iteration and loss are not lost) and the last (fraction 1)."""
        try:
            now = time.monotonic()
            stage = event.get("stage")
            fraction = event.get("fraction")
            new_stage = stage != self._last_stage
            if not (new_stage or now - self._last_progress >= PROGRESS_INTERVAL
                    or (fraction is not None and fraction >= 1)):
                self._held = dict(event)
                return
            if new_stage and self._held is not None:
                self.send(protocol.progress_event(dict(self._held)))
            self._held = None
            self._last_progress, self._last_stage = now, stage
            self.send(protocol.progress_event(dict(event)))
        except Exception:  # noqa: BLE001 - a progress report must never stop the job
            traceback.print_exc()


def claim_stdout() -> int:
    """Duplicate the original stdout for the protocol and send everything else written to fd 1
    or ``sys.stdout`` to stderr. Returns the protocol file descriptor."""
    sys.stdout.flush()
    proto_fd = os.dup(1)
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    return proto_fd


def watch_stdin(stdin, cancel: threading.Event) -> threading.Thread:
    """Set ``cancel`` on a cancel line or when stdin closes (the parent died)."""

    def run():
        try:
            for raw in iter(stdin.readline, b""):
                if not raw.strip():
                    continue
                try:
                    message = protocol.decode(raw)
                except protocol.ProtocolError as exc:
                    print(f"blender_match.worker: ignored control line: {exc}", file=sys.stderr)
                    continue
                if message["type"] == "cancel":
                    cancel.set()
        except (OSError, ValueError):
            pass
        cancel.set()  # end of input: nobody is listening any more

    thread = threading.Thread(target=run, name="stdin-watch", daemon=True)
    thread.start()
    return thread


def missing_packages() -> list[str]:
    """The worker's requirements (pip names) this Python cannot import."""
    return [name for name, module in WORKER_IMPORTS.items() if importlib.util.find_spec(module) is None]


def dependency_message(names) -> str:
    return (f"the worker Python {sys.executable} has no {', '.join(names)}: "
            "set up the backend in the add-on's preferences")


def check_dependencies() -> None:
    missing = missing_packages()
    if missing:
        raise DependencyError(dependency_message(missing))


def probe() -> dict:
    """What the add-on's preferences show: this Python, torch and the devices it can use."""
    check_dependencies()
    import torch  # here, not at the top: a missing torch must be reported, not crash the import

    devices = [{"id": "cpu", "name": platform.processor() or platform.machine() or "CPU"}]
    if torch.cuda.is_available():
        for i in range(torch.cuda.device_count()):
            devices.append({"id": "cuda" if i == 0 else f"cuda:{i}", "name": torch.cuda.get_device_name(i)})
    mps = getattr(torch.backends, "mps", None)
    if mps is not None and mps.is_available():
        devices.append({"id": "mps", "name": "Apple Metal"})
    packages: dict[str, str | None] = {}
    for name, module in WORKER_IMPORTS.items():
        try:
            imported = importlib.import_module(module)
            try:
                packages[name] = importlib.metadata.version(name)
            except importlib.metadata.PackageNotFoundError:
                packages[name] = getattr(imported, "__version__", None)
        except Exception as exc:  # noqa: BLE001 - installed but broken: show it, the job will fail clearly
            packages[name] = f"unusable: {protocol.one_line(str(exc), 200)}"
    return {
        "python": sys.executable,
        "python_version": platform.python_version(),
        "platform": platform.platform(),
        "torch": torch.__version__,
        "cuda": torch.version.cuda,
        "devices": devices,
        "packages": packages,
        "blender_match": __version__,
        "package": str(Path(__file__).resolve().parents[1]),
        "protocol": protocol.PROTOCOL_VERSION,
        "pid": os.getpid(),
    }


def run_request(request: dict, channel: Channel, cancel: threading.Event) -> dict:
    kind = request["type"]
    if kind == "probe":
        return probe()
    check_dependencies()
    from .. import pipeline  # here, not at the top: torch may be missing (a dependency error, above)

    if kind == "match":
        try:
            options = pipeline.MatchOptions(**request.get("options") or {})
        except TypeError as exc:
            raise protocol.ProtocolError(f"match options: {exc}") from None
        return pipeline.match_photo(Path(request["photo"]), Path(request["out_dir"]), options,
                                    progress=channel.progress, cancel=cancel.is_set)
    if kind == "render":
        return pipeline.render_params(Path(request["params_file"]), Path(request["out_dir"]), request["size"],
                                      device=request.get("device") or "auto",
                                      overwrite=bool(request.get("overwrite")),
                                      progress=channel.progress, cancel=cancel.is_set)
    raise protocol.ProtocolError(f"not a job request: {kind}")


def classify(exc: BaseException) -> tuple[str, str]:
    """(kind, one-line message) for an exception a job raised."""
    if isinstance(exc, DependencyError):
        return "dependency", str(exc)
    if isinstance(exc, ImportError):
        name = (getattr(exc, "name", None) or "").partition(".")[0]
        package = __package__.partition(".")[0]
        if isinstance(exc, ModuleNotFoundError) and name and name != package:
            pip_name = next((p for p, m in WORKER_IMPORTS.items() if m == name), name)
            return "dependency", dependency_message([pip_name])
        return "crash", f"{type(exc).__name__}: {exc}"
    if isinstance(exc, MemoryError) or type(exc).__name__ == "OutOfMemoryError":
        return "user", f"out of memory: {exc} (use a smaller size or the CPU)"
    if isinstance(exc, (BlenderMatchError, OSError)):
        return "user", str(exc) or type(exc).__name__
    return "crash", f"internal error (a bug; the worker's log has its traceback): {type(exc).__name__}: {exc}"


def main() -> int:
    keep_freed_memory()
    channel = Channel(claim_stdout())
    stdin = sys.stdin.buffer
    raw = stdin.readline()
    try:
        request = protocol.decode(raw)
        if not protocol.is_request(request):
            raise protocol.ProtocolError(f"expected a request ({', '.join(protocol.REQUEST_TYPES)}), "
                                         f"got {request['type']!r}")
    except protocol.ProtocolError as exc:
        channel.send(protocol.error_event(f"bad request: {exc}", "crash"))
        return 2
    cancel = threading.Event()
    watch_stdin(stdin, cancel)
    try:
        report = run_request(request, channel, cancel)
    except BaseException as exc:  # noqa: BLE001 - every outcome must reach the parent as one line
        if isinstance(exc, Cancelled) or (isinstance(exc, KeyboardInterrupt) and cancel.is_set()):
            channel.send(protocol.cancelled_event())
            return 0
        kind, message = classify(exc)
        if kind == "crash":
            traceback.print_exc()
        else:
            print(f"blender_match.worker: {kind} error: {message}", file=sys.stderr)
        channel.send(protocol.error_event(message, kind))
        return 1
    channel.send(protocol.result_event(report if isinstance(report, dict) else {"value": report}))
    return 0


if __name__ == "__main__":
    code = main()
    sys.stderr.flush()
    # Leave without waiting for non-daemon threads a library may have started.
    os._exit(code)
