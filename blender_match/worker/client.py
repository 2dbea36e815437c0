"""Blender's side of the worker: start ``python -m blender_match.worker`` with the backend's
Python, send it a request and poll its events from a timer, never blocking Blender's main thread.

    job = WorkerJob(python, protocol.match_request(photo, out_dir, {"graph": "plaster"}))
    ... every 0.1 s, on the main thread:
    for event in job.poll():          # progress dicts, then one result / error / cancelled
        ...
    job.state                         # running, finished, failed or cancelled
    job.result, job.error_message     # the report; the one-line error

Standard library only: Blender imports this (no torch, no bpy).
"""
from __future__ import annotations

import collections
import os
import queue
import signal
import subprocess
import threading
import time
from pathlib import Path

from . import protocol
from .backend_setup import clean_env, popen_flags, venv_python
from .polling import Polled

# The folder holding the ``blender_match`` package: the repository in development, Blender's
# ``extensions/user_default`` once installed as an extension (its folder is named blender_match).
PACKAGE_ROOT = Path(__file__).resolve().parents[2]
PACKAGE_NAME = Path(__file__).resolve().parents[1].name
CANCEL_GRACE_SECONDS = 5.0
STDERR_TAIL_LINES = 200

_EOF = object()


def find_worker_python(preferred: str | None, backend_venv=None) -> str | None:
    """The Python to run the worker with: ``preferred`` (the add-on preference) if it is set and
    executable, else the backend's virtual environment ``backend_venv`` if it has a Python, else
    None (the add-on then asks the user to set up the backend)."""
    if preferred:
        path = Path(os.path.expanduser(str(preferred).strip()))
        if path.is_file() and os.access(path, os.X_OK):
            return str(path)
    if backend_venv:
        path = venv_python(backend_venv)
        if path.is_file() and os.access(path, os.X_OK):
            return str(path)
    return None


def _describe_exit(code: int | None) -> str:
    if code is None:
        return "an unknown status"
    if code < 0:
        try:
            return f"code {code} (killed by {signal.Signals(-code).name})"
        except ValueError:
            return f"code {code} (killed by signal {-code})"
    return f"code {code}"


class WorkerJob(Polled):
    """One worker process running one request (see ``protocol``).

    ``python``: the worker's Python; ``request``: a request dict (``protocol.match_request`` …);
    ``pythonpath``: folders to put on the worker's PYTHONPATH (default: the folder containing this
    package); ``cwd``: its working folder; ``env``: extra environment variables.

    Reader threads move the worker's protocol lines into a queue and keep the last lines of its
    stderr (``stderr_tail``); ``poll()`` hands the events to the caller. Lines on the protocol
    stream that are not protocol are kept with stderr and otherwise ignored.
    """

    def __init__(self, python, request: dict, *, pythonpath=None, cwd=None, env: dict | None = None,
                 grace_seconds: float = CANCEL_GRACE_SECONDS):
        protocol.validate(request)
        if not protocol.is_request(request):
            raise protocol.ProtocolError(f"not a request: {request['type']!r}")
        self.python = str(python)
        self.request = request
        self.grace_seconds = grace_seconds
        self.state = "running"
        self.result: dict | None = None
        self.error_message: str | None = None
        self.error_kind: str | None = None
        self.progress: dict | None = None  # the latest progress event
        self.returncode: int | None = None
        self.stderr_tail: collections.deque[str] = collections.deque(maxlen=STDERR_TAIL_LINES)
        self._queue: queue.Queue = queue.Queue()
        self._stderr_lock = threading.Lock()
        self._terminal_seen = False
        self._stdout_done = False
        self._cancel_requested_at: float | None = None
        self._terminated_at: float | None = None
        self._pending: list[dict] = []
        self.process: subprocess.Popen | None = None
        self._threads: list[threading.Thread] = []

        paths = [PACKAGE_ROOT] if pythonpath is None else (
            [pythonpath] if isinstance(pythonpath, (str, Path)) else list(pythonpath))
        full_env = clean_env({"PYTHONPATH": os.pathsep.join(str(p) for p in paths),
                              "PYTHONUNBUFFERED": "1", "PYTHONIOENCODING": "utf-8", **(env or {})})
        try:
            self.process = subprocess.Popen(
                [self.python, "-m", f"{PACKAGE_NAME}.worker"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                stderr=subprocess.PIPE, cwd=cwd, env=full_env, **popen_flags())
        except OSError as exc:
            self._finish_error(f"cannot start the worker Python {self.python}: {exc.strerror or exc}", "dependency")
            return
        self._start_reader(self._read_stdout, "stdout")
        self._start_reader(self._read_stderr, "stderr")
        self._send(request)

    # --- background threads ----------------------------------------------------------------------

    def _start_reader(self, target, name):
        thread = threading.Thread(target=target, name=f"blender-match-worker-{name}", daemon=True)
        thread.start()
        self._threads.append(thread)

    def _read_stdout(self):
        stream = self.process.stdout
        try:
            for raw in iter(stream.readline, b""):
                if not raw.strip():
                    continue
                try:
                    self._queue.put(protocol.decode(raw))
                except protocol.ProtocolError:
                    self._keep_stderr("[stdout] " + raw.decode("utf-8", "replace").rstrip())
        except (OSError, ValueError):
            pass
        finally:
            self._queue.put(_EOF)

    def _read_stderr(self):
        try:
            for raw in iter(self.process.stderr.readline, b""):
                self._keep_stderr(raw.decode("utf-8", "replace").rstrip())
        except (OSError, ValueError):
            pass

    def _keep_stderr(self, line: str):
        with self._stderr_lock:
            self.stderr_tail.append(line)

    # --- the caller's side -----------------------------------------------------------------------

    @property
    def pid(self) -> int | None:
        return self.process.pid if self.process is not None else None

    @property
    def done(self) -> bool:
        return self.state != "running"

    def stderr_text(self, lines: int | None = None) -> str:
        with self._stderr_lock:
            tail = list(self.stderr_tail)
        return "\n".join(tail if lines is None else tail[-lines:])

    def poll(self) -> list[dict]:
        """Events since the last call; never blocks. After the worker's last event, or when it
        exits without one (a crash, killed), ``state`` is final; an exit without a result yields an
        error event naming the exit code and the end of stderr."""
        events, self._pending = self._pending, []
        while True:
            try:
                item = self._queue.get_nowait()
            except queue.Empty:
                break
            if item is _EOF:
                self._stdout_done = True
                continue
            if self._terminal_seen:
                continue  # nothing counts after the worker's last word
            events.append(item)
            self._apply(item)
        if self.process is not None:
            self._escalate_cancel()
            if self._stdout_done and self.returncode is None:
                self.returncode = self.process.poll()
            if self._stdout_done and self.returncode is not None and not self._terminal_seen:
                events.append(self._exit_event())
                self._apply(events[-1])
            if self.returncode is not None:
                self._close_pipes()
        return events

    def _apply(self, event: dict):
        kind = event["type"]
        if kind == "progress":
            self.progress = event
        elif kind == "result":
            self._terminal_seen, self.state, self.result = True, "finished", event["report"]
        elif kind == "error":
            self._terminal_seen, self.state = True, "failed"
            self.error_message, self.error_kind = event["message"], event["kind"]
        elif kind == "cancelled":
            self._terminal_seen, self.state = True, "cancelled"

    def _exit_event(self) -> dict:
        for thread in self._threads:  # let the stderr reader catch the last lines
            thread.join(timeout=1.0)
        if self._cancel_requested_at is not None:
            return protocol.cancelled_event()
        tail = [line for line in self.stderr_text(8).splitlines() if line.strip()]
        last = " | ".join(tail[-4:]) if tail else "no output on stderr"
        return protocol.error_event(
            f"the worker exited with {_describe_exit(self.returncode)} without a result; last output: {last}",
            "crash")

    def _finish_error(self, message: str, kind: str):
        event = protocol.error_event(message, kind)
        self._apply(event)
        self._pending.append(event)

    def _send(self, message: dict) -> bool:
        stdin = self.process.stdin if self.process is not None else None
        if stdin is None:  # never started (stdin is a pipe once it has)
            return False
        try:
            stdin.write(protocol.encode(message))
            stdin.flush()
            return True
        except (OSError, ValueError):  # the worker is gone or stdin already closed
            return False

    def cancel(self) -> None:
        """Ask the worker to stop (a cancel line, then stdin closed); ``poll`` terminates it after
        ``grace_seconds`` and kills it after as long again. The state becomes cancelled unless the
        worker finished first."""
        if self.process is None or self.done or self._cancel_requested_at is not None:
            return
        self._cancel_requested_at = time.monotonic()
        self._send(protocol.cancel_message())
        try:
            if self.process.stdin is not None:
                self.process.stdin.close()
        except OSError:
            pass
        self._escalate_cancel()

    def kill(self) -> None:
        """Stop the worker now (e.g. when the add-on is disabled)."""
        if self.process is not None and self.process.poll() is None:
            if self._cancel_requested_at is None:
                self._cancel_requested_at = time.monotonic()
            self.process.kill()

    def _escalate_cancel(self):
        if self._cancel_requested_at is None or self.process.poll() is not None:
            return
        now = time.monotonic()
        if self._terminated_at is None and now - self._cancel_requested_at >= self.grace_seconds:
            self._terminated_at = now
            self.process.terminate()
        elif self._terminated_at is not None and now - self._terminated_at >= self.grace_seconds:
            self.process.kill()

    def _close_pipes(self):
        """Once the worker has exited and the readers are done, release the pipes."""
        if any(t.is_alive() for t in self._threads):
            return
        for stream in (self.process.stdin, self.process.stdout, self.process.stderr):
            try:
                if stream is not None and not stream.closed:
                    stream.close()
            except OSError:
                pass
