"""The add-on's jobs, driven from Blender's main thread: one controller for the interface (a modal
operator polls it every 0.1 s) and for scripts (``wait=True``, or ``blender --background``, where
no timer runs: the operator polls it in a loop). Tests drive the same controllers.

    job = start_match(context, photo=PATH, graph="plaster", size=2048, quality="balanced")
    while not job.poll():           # never blocks; True once the job is over
        time.sleep(0.05)
    job.state                       # finished, failed or cancelled
    job.message                     # one line for the user (the result, the error, "cancelled")
    job.material_name               # the new material (finished)

A match runs ``pipeline.match_photo`` in a worker process (``worker.client.WorkerJob``; Blender's
Python has no torch) writing into a new result folder; when it finishes, a new material is built
from the folder and put in the active slot of the object that was active when the job started.
A re-render (``start_render``) runs ``pipeline.render_params`` from a material's stored (or
edited) parameters into a new folder and puts the new material where the old one was.

Nothing in the .blend changes until a job has finished: a failed or cancelled job leaves the file
exactly as it was, and removes the result folder it created (and the temporary files it wrote).
Running jobs live in ``JOBS`` (one per scene); the outcome of the last one in ``LAST``; the
backend setup and the worker probe (not bound to a scene) in ``SERVICES``; modal timers in
``TIMERS`` so that disabling the add-on (``shutdown``) stops and removes everything.
"""
from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
from pathlib import Path

import bpy

from ..errors import BlenderMatchError
from ..vocabulary import DEFAULT_QUALITY, FITTING, STAGE_TITLES
from ..worker import client, protocol
from ..worker.backend_setup import BackendSetup
from . import addon, parameters
from .material_builder import MATCH_ORIGIN, assign_material, build_material, fitted_zoom

JOBS: dict = {}      # scene key -> the scene's running job
LAST: dict = {}      # scene key -> {"state", "message", "graph", "loss", "seconds", "material", "folder", ...}
SERVICES: dict = {}  # "probe" / "setup" -> the running or last ProbeJob / SetupJob
TIMERS: dict = {}    # key -> (window_manager, timer) of a running modal operator



class JobError(addon.AddonError):
    """A job that cannot start (the message says why); nothing was changed."""


def stage_text(event: dict | None) -> str:
    """The progress bar's text for a worker progress event: "Fitting graph 1 of 3 (plaster)"…"""
    if not event:
        return "Starting the worker"
    stage = event.get("stage") or ""
    if stage == FITTING:
        index, count = event.get("graph_index"), event.get("graph_count")
        text = f"Fitting graph {index} of {count}" if index and count else "Fitting"
        if event.get("graph"):
            text += f" ({event['graph']})"
        if event.get("iteration") is not None and event.get("iterations"):
            text += f", iteration {event['iteration']}/{event['iterations']}"
        return text
    return STAGE_TITLES.get(stage, stage.capitalize())


class _Job:
    """What every add-on job has: a worker process, progress, a final state and message."""

    kind = "job"

    def __init__(self, worker: client.WorkerJob):
        self.worker = worker
        self.state = "running"
        self.message = ""
        self.progress: dict | None = None
        self.fraction = 0.0
        self.eta_seconds = None
        self.started = time.monotonic()
        self.cancel_requested = False

    @property
    def done(self) -> bool:
        return self.state != "running"

    @property
    def pid(self) -> int | None:
        return self.worker.pid

    @property
    def stage_text(self) -> str:
        if self.cancel_requested and not self.done:
            return "Cancelling"
        return stage_text(self.progress)

    @property
    def elapsed(self) -> float:
        return time.monotonic() - self.started

    def progress_text(self) -> str:
        text = self.stage_text
        if self.eta_seconds is not None and not self.cancel_requested:
            text += f", {addon.format_seconds(self.eta_seconds)} left"
        return text

    def poll(self) -> bool:
        """Handle the worker's events since the last call (main thread only; never blocks);
        finish the job once the worker is done. True when the job is over."""
        if self.done:
            return True
        for event in self.worker.poll():
            if event["type"] == "progress":
                self.progress = event
                if isinstance(event.get("fraction"), (int, float)):
                    self.fraction = max(self.fraction, min(1.0, float(event["fraction"])))
                self.eta_seconds = event.get("eta_seconds")
        if self.worker.done:
            self._end()
        return self.done

    def wait(self, timeout: float | None = None, interval: float = 0.05) -> bool:
        """Poll until the job is over (or ``timeout`` seconds); True when it is over."""
        deadline = None if timeout is None else time.monotonic() + timeout
        try:
            while not self.poll():
                if deadline is not None and time.monotonic() > deadline:
                    return False
                time.sleep(interval)
        except KeyboardInterrupt:
            self.cancel()
            while not self.poll():
                time.sleep(interval)
        return True

    def cancel(self) -> None:
        """Ask the worker to stop; ``poll`` finishes the job (cancelled) once it has."""
        if not self.done:
            self.cancel_requested = True
            self.worker.cancel()

    def kill(self) -> None:
        """Stop the worker now and end the job as cancelled (the add-on is being disabled)."""
        if self.done:
            return
        self.cancel_requested = True
        self.worker.kill()
        if self.worker.process is not None:
            try:
                self.worker.process.wait(timeout=5)
            except Exception:  # noqa: BLE001 - it was killed; the readers end with it
                pass
        deadline = time.monotonic() + 5
        while not self.worker.done and time.monotonic() < deadline:
            self.worker.poll()
            time.sleep(0.02)
        if not self.worker.done:
            self.worker.state = "cancelled"
        self._end()

    def _end(self):
        state = self.worker.state
        try:
            if state == "finished":
                self.on_finished(self.worker.result or {})
            elif state == "cancelled":
                self.state, self.message = "cancelled", "Cancelled: nothing was changed"
                self.on_stopped()
            else:
                self.state = "failed"
                self.message = self.worker.error_message or "the worker failed without a message"
                self.on_stopped()
        except Exception as exc:  # noqa: BLE001 - a job must always end, with a message
            self.state = "failed"
            self.message = str(exc) if isinstance(exc, BlenderMatchError) else f"{type(exc).__name__}: {exc}"
            try:
                self.on_stopped()
            except Exception:  # noqa: BLE001
                pass
        finally:
            self.on_done()

    # hooks
    def on_finished(self, report: dict):
        self.state, self.message = "finished", "done"

    def on_stopped(self):
        """Failed or cancelled: undo what the job prepared (folders, temporary files)."""

    def on_done(self):
        """Always, last: leave the registry."""


# --- scene jobs: a match, a re-render ------------------------------------------------------------


def _remove_folders(folders):
    """Remove the folders a job created: the result folder with whatever the worker left in it
    (it was created empty for this job), then its parents when they are empty."""
    for i, folder in enumerate(folders):
        folder = Path(folder)
        try:
            if i == 0:
                shutil.rmtree(folder, ignore_errors=True)
            elif folder.is_dir() and not any(folder.iterdir()):
                folder.rmdir()
        except OSError:
            pass


class _SceneJob(_Job):
    """A job that ends in a new material in a scene."""

    def __init__(self, worker, *, scene, out_dir: Path, created: list, pack: bool, tiling: float,
                 object_name: str | None, slot_index: int, temp_files=(), notes=(), origin: dict | None = None):
        super().__init__(worker)
        self.origin = dict(origin or {})  # what the match came from, for the material's record
        self.scene_key = addon.scene_key(scene)
        self.scene_name = scene.name
        self.out_dir = Path(out_dir)
        self.created = list(created)
        self.pack = pack
        self.tiling = tiling
        self.object_name = object_name
        self.slot_index = slot_index
        self.temp_files = list(temp_files)
        self.notes = list(notes)
        self.material_name: str | None = None
        self.report: dict | None = None
        JOBS[self.scene_key] = self

    def on_stopped(self):
        _remove_folders(self.created)
        outcome = {"state": self.state, "message": self.message, "kind": self.kind}
        if self.state == "failed":
            outcome["error"] = self.message
        LAST[self.scene_key] = outcome

    def on_done(self):
        for path in self.temp_files:
            try:
                Path(path).unlink(missing_ok=True)
            except OSError:
                pass
        if JOBS.get(self.scene_key) is self:
            del JOBS[self.scene_key]

    def _build(self, report: dict, name=None):
        """A new material from the result folder (any datablock made before an error is removed)."""
        before_materials, before_images = set(bpy.data.materials), set(bpy.data.images)
        try:
            material = build_material(self.out_dir, name=name, pack=self.pack, tiling=self.tiling,
                                      origin=self.origin)
            parameters.populate(material)
        except BaseException:
            for image in set(bpy.data.images) - before_images:
                bpy.data.images.remove(image)
            for material in set(bpy.data.materials) - before_materials:
                bpy.data.materials.remove(material)
            raise
        if addon.blend_is_saved() and bpy.context.preferences.filepaths.use_relative_paths:
            for node in material.node_tree.nodes:  # "//blender_match/...": the project folder can move
                image = getattr(node, "image", None)
                if image is not None and image in set(bpy.data.images) - before_images and not image.packed_file:
                    try:
                        image.filepath = bpy.path.relpath(image.filepath)
                    except ValueError:  # another drive (Windows): keep it absolute
                        pass
        self.material_name = material.name
        self.report = report
        return material

    def _outcome(self, report: dict, **extra) -> dict:
        outcome = {"state": "finished", "kind": self.kind, "graph": report.get("graph"),
                   "loss": report.get("loss_final"), "seconds": report.get("seconds"),
                   "size": report.get("size"), "material": self.material_name, "folder": str(self.out_dir),
                   "message": self.message, **extra}
        LAST[self.scene_key] = outcome
        return outcome


class MatchJob(_SceneJob):
    kind = "match"

    def on_finished(self, report: dict):
        material = self._build(report)
        obj = bpy.data.objects.get(self.object_name) if self.object_name else None
        assigned_to = None  # the name of the object the material went on
        if obj is not None and hasattr(obj.data, "materials"):
            if obj.material_slots and 0 <= self.slot_index < len(obj.material_slots):
                obj.material_slots[self.slot_index].material = material
                assigned_to = obj.name
            elif assign_material(obj, material):
                assigned_to = obj.name
        loss = report.get("loss_final")
        text = f"Matched {report.get('graph')}: material \"{material.name}\""
        text += f" on {assigned_to}" if assigned_to is not None else " (no object to put it on)"
        if isinstance(loss, (int, float)):
            text += f", loss {loss:.4g}"
        if isinstance(report.get("seconds"), (int, float)):
            text += f", {addon.format_seconds(report['seconds'])}"
        text += f"; maps in {self.out_dir}"
        if self.notes:
            text += "; " + "; ".join(self.notes)
        self.state, self.message = "finished", text
        self._outcome(report, object=assigned_to)


class RenderJob(_SceneJob):
    """A re-render of a material's stored (``kind`` "render") or edited ("edit") parameters."""

    def __init__(self, worker, *, old_material: str, kind: str = "render", **kwargs):
        super().__init__(worker, **kwargs)
        self.kind = kind
        self.old_material = old_material

    def on_finished(self, report: dict):
        material = self._build(report)
        obj = bpy.data.objects.get(self.object_name) if self.object_name else None
        old = bpy.data.materials.get(self.old_material)
        placed_on = None  # the name of the object whose slot now holds the new material
        if obj is not None and old is not None:
            placed = self._slot_holding(list(obj.material_slots), old)
            if placed is not None:
                obj.material_slots[placed].material = material
                placed_on = obj.name
        what = "Edited" if self.kind == "edit" else "Re-rendered"
        size = report.get("size")
        text = f"{what} \"{self.old_material}\" at {size} px: new material \"{material.name}\""
        text += f" on {placed_on}" if placed_on is not None else " (the old one is no longer in a slot: not assigned)"
        text += f"; maps in {self.out_dir}"
        if self.notes:
            text += "; " + "; ".join(self.notes)
        self.state, self.message = "finished", text
        self._outcome(report, object=placed_on, replaced=self.old_material)

    def _slot_holding(self, slots: list, old) -> int | None:
        """The job's slot when it still holds ``old``; else (the slots changed while the job ran)
        the first slot that does; None when none does."""
        if 0 <= self.slot_index < len(slots) and slots[self.slot_index].material == old:
            return self.slot_index
        return next((i for i, s in enumerate(slots) if s.material == old), None)


# --- starting jobs -------------------------------------------------------------------------------


def running_job(scene):
    job = JOBS.get(addon.scene_key(scene))
    return job if job is not None and not job.done else None


def _check_idle(scene):
    job = running_job(scene)
    if job is not None:
        raise JobError(f"a {job.kind} job is already running in scene {scene.name!r}: wait or cancel it")


def _target(context):
    obj = addon.active_object(context)
    if obj is None:
        return None, 0
    return obj.name, obj.active_material_index


def image_photo(image) -> tuple[Path, bool]:
    """The photo file of an image datablock: its own file when it is on disk unchanged, else a
    temporary PNG written from its pixels. (path, whether it is temporary)."""
    if image is None:
        raise JobError("no photo image chosen")
    if image.source == "FILE" and not image.packed_file and not image.is_dirty and image.filepath:
        path = Path(bpy.path.abspath(image.filepath, library=image.library))
        if path.is_file():
            return path, False
    if not image.has_data:
        try:
            image.reload()
        except RuntimeError:
            pass
    width, height = image.size
    if not (width and height):
        raise JobError(f"image {image.name!r} has no pixels to match")
    fd, tmp = tempfile.mkstemp(prefix="blender_match_photo_", suffix=".png", dir=bpy.app.tempdir or None)
    os.close(fd)
    scene = bpy.data.scenes.new("blender_match photo")
    try:
        # Standard view: the file holds the image's colours, not a tone-mapped display of them.
        scene.view_settings.view_transform = "Standard"
        scene.view_settings.look = "None"
        scene.view_settings.exposure = 0.0
        scene.view_settings.gamma = 1.0
        settings = scene.render.image_settings
        settings.file_format = "PNG"
        settings.color_mode = "RGB"
        settings.color_depth = "16" if image.is_float else "8"
        image.save_render(tmp, scene=scene)
    except RuntimeError as exc:
        Path(tmp).unlink(missing_ok=True)
        raise JobError(f"image {image.name!r} cannot be written as a photo: {str(exc).strip()}") from None
    finally:
        bpy.data.scenes.remove(scene)
    return Path(tmp), True


def _worker(python: str, request: dict) -> client.WorkerJob:
    worker = client.WorkerJob(python, request)
    if worker.done and worker.state == "failed":  # the Python could not even start
        raise JobError(f"{addon.NO_BACKEND} ({worker.error_message})")
    return worker


def start_match(context, *, photo=None, image=None, graph="AUTO", size=2048, quality=DEFAULT_QUALITY,
                device="default", seed=0, pack=False, tiling=1.0, iterations=0, calibrate=True,
                match_scale=False, alternatives=()) -> MatchJob:
    """Start matching the photo (a file path, or an image datablock ``image``) with ``graph``
    ('AUTO': automatic selection); JobError when it cannot start (nothing changed then).
    ``alternatives``: graphs an earlier automatic match of the photo ranked near ``graph``, which
    the new material offers (an automatic match's own ranking replaces them)."""
    scene = context.scene
    _check_idle(scene)
    python = worker_python(context)
    temp_files = []
    if image is not None:
        path, temporary = image_photo(image)
        if temporary:
            temp_files.append(path)
    else:
        if not photo:
            raise JobError("no photo chosen: pick a photo file or an image")
        path = Path(bpy.path.abspath(str(photo)))
        if not path.is_file():
            raise JobError(f"{path}: photo not found")
    notes = []
    if not addon.blend_is_saved():
        pack = True
        notes.append("the .blend is not saved, so the maps went to a temporary folder and are packed into it")
    auto = graph in ("AUTO", "", None)
    try:
        out_dir, created = addon.new_result_folder("auto" if auto else graph)
    except addon.AddonError as exc:
        for tmp in temp_files:
            Path(tmp).unlink(missing_ok=True)
        raise JobError(str(exc)) from None
    options = {"graph": None if auto else graph, "size": int(size), "quality": quality, "seed": int(seed),
               "device": addon.resolve_device(device, context), "overwrite": False,
               "iterations": int(iterations) if iterations else None, "calibrate": bool(calibrate),
               "zoom": None if match_scale else 1.0}
    try:
        worker = _worker(python, protocol.match_request(path, out_dir, options))
    except BaseException:
        _remove_folders(created)
        for tmp in temp_files:
            Path(tmp).unlink(missing_ok=True)
        raise
    object_name, slot = _target(context)
    origin: dict = {"photo_image": image.name} if image is not None else {"photo": str(photo)}
    origin["quality"] = quality
    origin["alternatives"] = [name.strip() for name in alternatives if name.strip() not in ("", graph)]
    return MatchJob(worker, scene=scene, out_dir=out_dir, created=created, pack=pack, tiling=tiling,
                    object_name=object_name, slot_index=slot, temp_files=temp_files, notes=notes, origin=origin)


def material_tiling(material, default: float = 1.0) -> float:
    """The user's tiling of a matched material: its "Tiling" mapping node's scale over the fit's
    zoom (``material_builder.fitted_zoom``), so a rebuilt material keeps both without doubling the zoom."""
    tree = getattr(material, "node_tree", None)
    node = tree.nodes.get("Tiling") if tree is not None else None
    if node is None or node.type != "MAPPING":
        return default
    scale = float(node.inputs["Scale"].default_value[0])
    try:
        zoom = fitted_zoom(parameters.stored_params(material))
    except parameters.ParameterError:
        zoom = 1.0
    return scale / zoom if scale > 0 else default


def start_render(context, material, size: int, *, values: dict | None = None, device="default",
                 pack=False) -> RenderJob:
    """Re-render ``material`` (made by a match) at ``size`` from its stored parameters, with
    ``values`` ({"exposed.NAME": value}) put in when given (an edit), into a new folder."""
    scene = context.scene
    _check_idle(scene)
    try:
        data = parameters.stored_params(material)
        if values:
            data = parameters.edited_params(data, values)
    except parameters.ParameterError as exc:
        raise JobError(str(exc)) from None
    python = worker_python(context)
    notes = []
    if not addon.blend_is_saved():
        pack = True
        notes.append("the .blend is not saved, so the maps went to a temporary folder and are packed into it")
    graph = data.get("graph") or data.get("source") or "material"
    kind = "edit" if values else "render"
    size_name = next((k for k, v in addon.SIZES.items() if v == size), str(size))
    stem = f"{graph}_edit" if values else f"{graph}_{size_name}"
    fd, params_file = tempfile.mkstemp(prefix="blender_match_params_", suffix=".json",
                                       dir=bpy.app.tempdir or None)
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1)
    try:
        out_dir, created = addon.new_result_folder(stem)
    except addon.AddonError as exc:
        Path(params_file).unlink(missing_ok=True)
        raise JobError(str(exc)) from None
    request = protocol.render_request(params_file, out_dir, int(size), device=addon.resolve_device(device, context))
    try:
        worker = _worker(python, request)
    except BaseException:
        _remove_folders(created)
        Path(params_file).unlink(missing_ok=True)
        raise
    object_name, slot = _target(context)
    record = parameters.stored_record(material) or {}
    origin = {key: record[key] for key in MATCH_ORIGIN if key in record}
    return RenderJob(worker, scene=scene, out_dir=out_dir, created=created, pack=pack,
                     tiling=material_tiling(material), object_name=object_name, slot_index=slot,
                     temp_files=[params_file], notes=notes, old_material=material.name, kind=kind, origin=origin)


def worker_python(context) -> str:
    try:
        return addon.worker_python(context)
    except addon.AddonError as exc:
        raise JobError(str(exc)) from None


# --- services: the worker probe and the backend setup --------------------------------------------


class ProbeJob(_Job):
    """``python -m blender_match.worker`` answering a probe: its Python, torch and devices."""

    kind = "probe"

    def __init__(self, worker) -> None:
        super().__init__(worker)
        self.report: dict | None = None
        SERVICES["probe"] = self

    def on_finished(self, report: dict):
        self.report = report
        self.state, self.message = "finished", probe_summary(report)

    def on_stopped(self):
        if self.state == "failed":
            self.message = f"The worker does not work: {self.message}"


def probe_summary(report: dict) -> str:
    devices = ", ".join(d.get("id", "?") + (f" ({d['name']})" if d.get("name") and d.get("id") != "cpu" else "")
                        for d in report.get("devices") or [])
    return (f"Worker Python {report.get('python_version', '?')} at {report.get('python', '?')}; "
            f"torch {report.get('torch', '?')}; devices: {devices or 'none'}")


def start_probe(context) -> ProbeJob:
    job = SERVICES.get("probe")
    if isinstance(job, ProbeJob) and not job.done:
        raise JobError("the worker test is already running")
    return ProbeJob(_worker(worker_python(context), protocol.probe_request()))


class SetupJob:
    """``backend_setup.BackendSetup`` behind the same interface as the other jobs."""

    kind = "setup"

    def __init__(self, target_dir, base_python, pip_args=()):
        self.setup = BackendSetup(target_dir, base_python, pip_args=pip_args)
        self.target_dir = Path(target_dir)
        self.state = "running"
        self.message = ""
        self.line = ""
        self.cancel_requested = False
        self.started = time.monotonic()
        SERVICES["setup"] = self

    @property
    def done(self) -> bool:
        return self.state != "running"

    @property
    def stage_text(self) -> str:
        if self.cancel_requested and not self.done:
            return "Cancelling"
        return (self.setup.stage or "starting").capitalize()

    @property
    def fraction(self) -> float:
        """A rough share of the work done (pip gives no total): by stage."""
        if self.done:
            return 1.0
        return {"creating the environment": 0.05, "installing packages": 0.3,
                "checking the packages": 0.95}.get(self.setup.stage, 0.0)

    def progress_text(self) -> str:
        return f"{self.stage_text}: {self.line}" if self.line else self.stage_text

    def poll(self) -> bool:
        if self.done:
            return True
        for event in self.setup.poll():
            if event["type"] == "progress":
                self.line = protocol.one_line(event.get("line") or "", 120)
        if self.setup.done:
            self.state = self.setup.state
            if self.state == "finished":
                self.message = f"Backend ready: {self.setup.python}"
            elif self.state == "cancelled":
                self.message = "Backend setup cancelled"
            else:
                self.message = f"Backend setup failed: {self.setup.error_message}"
        return self.done

    def wait(self, timeout=None, interval=0.1) -> bool:
        deadline = None if timeout is None else time.monotonic() + timeout
        while not self.poll():
            if deadline is not None and time.monotonic() > deadline:
                return False
            time.sleep(interval)
        return True

    def cancel(self):
        if not self.done:
            self.cancel_requested = True
            self.setup.cancel()

    kill = cancel


def start_setup(base_python: str, pip_args=()) -> SetupJob:
    job = SERVICES.get("setup")
    if isinstance(job, SetupJob) and not job.done:
        raise JobError("the backend setup is already running")
    base = Path(os.path.expanduser(base_python))
    if not base.is_file():
        raise JobError(f"cannot set up the backend: the Python {base} does not exist")
    return SetupJob(addon.backend_dir(create=True), str(base), pip_args)


# --- modal timers and shutdown -------------------------------------------------------------------


def add_timer(key, window_manager, window, interval: float = 0.1):
    timer = window_manager.event_timer_add(interval, window=window)
    TIMERS[key] = (window_manager, timer)
    return timer


def remove_timer(key):
    entry = TIMERS.pop(key, None)
    if entry is not None:
        wm, timer = entry
        try:
            wm.event_timer_remove(timer)
        except (ReferenceError, ValueError, RuntimeError):
            pass


def shutdown():
    """Stop every job and timer (the add-on is being disabled): workers are killed, their
    folders removed, nothing is built."""
    for key in list(TIMERS):
        remove_timer(key)
    for job in list(JOBS.values()):
        job.kill()
    for job in list(SERVICES.values()):
        if not job.done:
            job.kill()
    JOBS.clear()
    LAST.clear()
    SERVICES.clear()
