"""Fitting a material graph's parameters to a photo (the MATch paper, section 4.1).

The loss is the texture-descriptor distance (``descriptor.style_loss``) between the flash render
of the graph's maps and the photo; Adam descends it in the graph's normalised parameter space and
the parameters are clamped to [0, 1] after every step, as in the paper.

The paper's optimiser renders at 512 px and describes at 512/256/128 every iteration with a fixed
learning rate of 5e-4 (``PAPER_SCHEDULE``). Ours (``QUALITY_SCHEDULES``) reaches the same loss
sooner by
- describing small: ``draft`` describes the render at 128 px, ``balanced`` and ``best`` at 256
  and 128 (at 128 alone the finest grain, 2 to 4 pixels at 512, is invisible to the descriptor and
  drifts freely), each with a 128-px window of it at full resolution (``TargetLoss``'s crop), and
  ``best`` ends with a few steps at 512. Every stage still *renders* at the photo's size (512 px): a
  graph rendered at 128 px is not the photo shrunk to 128, because the flash shading of fine
  relief does not average linearly (a height map's fine detail tilts the normals only at the
  resolution that holds it, so most library graphs render brighter at 128 than at 512 shrunk to
  128). A fit whose early stages rendered at 128 px darkened the material to compensate and lost
  its fine grain, and came out too dark at the size the maps are written. VGG19 costs more than
  the graph, so describing small keeps most of the speed (figures: docs/matching.md);
- larger learning rates with a cosine decay inside each stage;
- early stopping on a plateau (no relative improvement of the best loss for ``patience``
  iterations ends the stage);
- the photo's descriptor computed once per stage (``TargetLoss``).
The result is the best parameters seen, not the last.

A fit is deterministic for a given graph seed on a given device and thread count; ``progress``
gets one event per iteration and ``cancel()`` is polled every iteration (``errors.Cancelled``).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import torch
import torch.nn.functional as F

from ..errors import Cancelled
from ..vocabulary import QUALITY_NAMES
from .calibration import framed_maps
from .descriptor import TextureDescriptor, style_loss
from .errors import DiffMatError
from .render import FlashCamera, render_maps


@dataclass(frozen=True)
class Stage:
    """``iterations`` Adam steps rendering at ``size`` px, describing at ``scales`` (and, with
    ``crop``, a ``crop`` x ``crop`` window of the render at full resolution: see ``TargetLoss``),
    learning rate ``lr`` reached by a linear warm-up over ``warmup`` steps (Adam's first steps
    move every parameter by about ``lr`` whatever its gradient, which throws a good start away),
    then decayed by a cosine to ``lr * final_lr_ratio``."""

    size: int
    scales: tuple[int, ...]
    iterations: int
    lr: float
    final_lr_ratio: float = 0.1
    warmup: int = 0
    crop: int | None = None


@dataclass(frozen=True)
class Schedule:
    """A sequence of stages; ``patience`` iterations without a relative improvement of
    ``min_improvement`` end a stage early (None: never)."""

    name: str
    stages: tuple[Stage, ...]
    patience: int | None = None
    min_improvement: float = 1e-3

    @property
    def iterations(self) -> int:
        return sum(s.iterations for s in self.stages)

    def scaled(self, iterations: int) -> "Schedule":
        """The same schedule with its iterations rescaled to ``iterations`` in all (at least one
        per stage), for tests and scripted drafts."""
        if iterations < 1:
            raise DiffMatError(f"iterations must be at least 1, got {iterations}")
        total = self.iterations
        stages = tuple(replace(s, iterations=max(1, round(s.iterations * iterations / total))) for s in self.stages)
        return Schedule(self.name, stages, self.patience, self.min_improvement)


PAPER_SCHEDULE = Schedule("paper", (Stage(512, (512, 256, 128), 2000, 5e-4, final_lr_ratio=1.0),))

# Learning rates measured on synthetic targets of plaster and bricks (60 steps at 128 px from the
# defaults): 0.02 was best or within noise of the best on both; 0.04 lost 8-20% on bricks. Stage
# sizes and iteration counts: `blender-match bench recovery` (docs/matching.md).
# One schedule per quality of the vocabulary (``QUALITY_NAMES``), keyed and ordered as it is: a
# quality added or renamed in one place and not the other fails here, at import.
_PRESETS = {schedule.name: schedule for schedule in (
    Schedule("draft", (Stage(512, (128,), 48, 0.02, warmup=5, crop=128),), patience=15),
    Schedule("balanced", (Stage(512, (256, 128), 90, 0.02, warmup=5, crop=128),), patience=25),
    Schedule("best", (Stage(512, (256, 128), 160, 0.02, warmup=5, crop=128), Stage(512, (512, 256, 128), 20, 0.003)),
             patience=40),
)}
if set(_PRESETS) != set(QUALITY_NAMES):
    raise RuntimeError(f"optimiser schedules {sorted(_PRESETS)} do not match the vocabulary's qualities "
                       f"{sorted(QUALITY_NAMES)}")
QUALITY_SCHEDULES = {name: _PRESETS[name] for name in QUALITY_NAMES}


def quality_schedule(quality: str, iterations: int | None = None) -> Schedule:
    """The ``quality`` preset (``QUALITY_SCHEDULES``), rescaled to ``iterations`` in all when given."""
    schedule = QUALITY_SCHEDULES[quality]
    return schedule if iterations is None else schedule.scaled(iterations)

def resize_square(image: torch.Tensor, size: int) -> torch.Tensor:
    """An (N, C, S, S) image resized to ``size`` (antialiased when shrinking)."""
    if image.shape[-1] == size:
        return image
    return F.interpolate(image, size=(size, size), mode="bilinear", antialias=True, align_corners=False)


def quarter_crop(image: torch.Tensor, size: int) -> torch.Tensor:
    """The ``size`` x ``size`` pixels of an (N, C, S, S) image around the point a quarter of its
    width in from its left and top edges (all of it when S <= size; kept inside the image)."""
    side = image.shape[-1]
    if side <= size:
        return image
    start = min(max(0, side // 4 - size // 2), side - size)
    return image[..., start:start + size, start:start + size]


class TargetLoss:
    """The descriptor loss against one photo, with the photo's descriptor cached per scale set.

    ``crop`` adds to the descriptor at ``scales`` that of a ``crop`` x ``crop`` window of the render
    and of the photo (resized to the render's size) at full resolution: described whole at 128 px,
    a 512-px image's grain of a few pixels and a leather's cells of 10 to 15 are averaged away, and
    the fit trades them for any texture of the same colour and contrast; the window shows them at
    their own size for the cost of one more 128-px description. The window (``quarter_crop``) is
    off the centre, where a flash photo's highlight sits: a centre window on a glossy photo
    describes the highlight's shape, not the grain. The photo's falloff lies in the window of both
    images alike (the render is under the photo's solved flash).
    """

    def __init__(self, photo: torch.Tensor, descriptor: TextureDescriptor, camera: FlashCamera = FlashCamera()):
        if photo.dim() != 4 or photo.shape[:2] != (1, 3):
            raise DiffMatError(f"target photo must be (1, 3, H, W), got {tuple(photo.shape)}")
        self.photo = photo
        self.descriptor = descriptor
        self.camera = camera
        self._targets: dict[tuple, torch.Tensor] = {}

    def target(self, scales: tuple[int, ...], crop: int | None = None, size: int | None = None) -> torch.Tensor:
        """The photo's descriptor at ``scales`` (and its ``crop`` window at the render's ``size``)."""
        key = (scales, crop, size if crop else None)
        if key not in self._targets:
            with torch.no_grad():
                photo = self.photo.to(self._device())
                full = resize_square(photo, size) if crop and size else photo
                self._targets[key] = self._describe(resize_square(photo, max(scales)), scales, crop, full)
        return self._targets[key]

    def _describe(self, image: torch.Tensor, scales: tuple[int, ...], crop: int | None,
                  full: torch.Tensor) -> torch.Tensor:
        described = self.descriptor(image, scales)
        if crop is None:
            return described
        window = quarter_crop(full, crop)
        return torch.cat([described, self.descriptor(window, (window.shape[-1],))], dim=1)

    def _device(self):
        return next(self.descriptor.parameters()).device

    def __call__(self, graph, theta: torch.Tensor, size: int, scales: tuple[int, ...], seed: int = 0,
                 crop: int | None = None):
        """Loss of each parameter vector in ``theta`` (B, P) rendered at ``size`` (at most the photo's
        own size; ``scales`` are capped the same way) and framed at the graph's zoom
        (``calibration.framed_maps``), described at ``scales`` and, when given, a ``crop`` x ``crop``
        window at full resolution (the whole render when it is no larger): a (B,) tensor."""
        side = self.photo.shape[-1]
        if size > side:
            size = side
            scales = tuple(dict.fromkeys(min(s, side) for s in scales))
        maps = framed_maps(graph, size, seed, theta)
        image = render_maps(maps, self.camera)
        if image.shape[0] != theta.shape[0]:
            image = image.expand(theta.shape[0], -1, -1, -1)
        return style_loss(self._describe(image, scales, crop, image), self.target(scales, crop, size))


@dataclass
class FitResult:
    """The best parameter vector found and how the fit went. ``history`` holds
    (seconds, iteration, loss) per iteration; ``stage_seconds`` one entry per stage run;
    ``stopped`` is "budget" (all iterations ran) or "plateau" (the last stage stopped early)."""

    theta: torch.Tensor
    loss_initial: float
    loss_final: float
    iterations: int
    seconds: float
    history: list[tuple[float, int, float]] = field(default_factory=list)
    stage_seconds: list[float] = field(default_factory=list)
    snapshots: list[tuple[float, torch.Tensor]] = field(default_factory=list)
    stopped: str = "budget"


def _stage_cost(stage: Stage) -> float:
    """Relative cost of one iteration of a stage (pixels rendered and described)."""
    return stage.size ** 2 + sum(s * s for s in stage.scales) + (stage.crop or 0) ** 2


def _learning_rate(stage: Stage, it: int) -> float:
    if it < stage.warmup:
        return stage.lr * (it + 1) / (stage.warmup + 1)
    ratio = stage.final_lr_ratio
    return stage.lr * (ratio + (1 - ratio) * 0.5 * (1 + math.cos(math.pi * it / max(1, stage.iterations))))


def _advance(value: torch.Tensor, current: float, theta: torch.Tensor, optimizer: torch.optim.Adam,
             best: torch.Tensor, lr: float) -> torch.optim.Adam:
    """One Adam step from the point just evaluated (loss ``value``, its float ``current``), kept in
    [0, 1]; after a non-finite loss, back to ``best`` with a fresh optimiser rather than follow a
    NaN. Returns the optimiser to go on with."""
    if math.isfinite(current):
        value.backward()
        if theta.grad is not None and torch.isfinite(theta.grad).all():
            optimizer.step()
    else:
        optimizer = torch.optim.Adam([theta], lr=lr)
    with torch.no_grad():
        if not math.isfinite(current):
            theta.copy_(best[None])
        theta.clamp_(0.0, 1.0)
    return optimizer


def final_stage_loss(loss: TargetLoss, graph, theta: torch.Tensor, schedule: Schedule, seed: int = 0) -> float:
    """The loss of the parameter vector ``theta`` (P,) as a fit on ``schedule`` measures its
    ``loss_initial`` and ``loss_final``: at its last stage's size, scales and window."""
    last = schedule.stages[-1]
    with torch.no_grad():
        return float(loss(graph, theta.reshape(1, -1), last.size, last.scales, seed, last.crop)[0])


def fit(graph, loss: TargetLoss, schedule: Schedule, *, seed: int = 0, theta0: torch.Tensor | None = None,
        progress=None, cancel=None, keep_snapshots: bool = False) -> FitResult:
    """Fit ``graph``'s trainable parameters to ``loss``'s photo following ``schedule``.

    ``theta0`` (P,) is the normalised start (default: the graph's current parameters); each stage
    starts from the best point of the one before. ``loss_initial`` and ``loss_final`` are both
    measured as the last stage measures (its size and scales), so they compare. The graph itself
    is left unchanged: apply ``result.theta`` with ``graph.set_vector``. ``keep_snapshots``
    records (seconds, theta) after every step (benchmarks re-score them afterwards).
    Raises DiffMatError when the graph has no trainable parameter or the start's loss is not
    finite, and Cancelled when ``cancel()`` returns True.
    """
    if graph.num_params() == 0:
        raise DiffMatError(f"graph {graph.name}: nothing to fit (no trainable parameter)")
    device = next(loss.descriptor.parameters()).device
    best = (graph.get_vector() if theta0 is None else theta0.detach().reshape(-1)).to(device).clamp(0, 1)
    t_start = time.perf_counter()
    loss_initial = final_stage_loss(loss, graph, best, schedule, seed)
    if not math.isfinite(loss_initial):
        raise DiffMatError(f"graph {graph.name}: the loss at the start is not finite")
    result = FitResult(theta=best, loss_initial=loss_initial, loss_final=loss_initial, iterations=0, seconds=0.0)
    costs = [_stage_cost(s) for s in schedule.stages]
    seconds_per_cost = None
    for index, stage in enumerate(schedule.stages):
        stage_start = time.perf_counter()
        theta = best.clone()[None].requires_grad_(True)
        optimizer = torch.optim.Adam([theta], lr=stage.lr)
        stage_best, plateau_ref, since_ref = math.inf, math.inf, 0
        result.stopped = "budget"
        for it in range(stage.iterations):
            if cancel is not None and cancel():
                raise Cancelled()
            t_iter = time.perf_counter()
            for group in optimizer.param_groups:
                group["lr"] = _learning_rate(stage, it)
            optimizer.zero_grad(set_to_none=True)
            value = loss(graph, theta, stage.size, stage.scales, seed, stage.crop)[0]
            current = float(value.detach())
            if math.isfinite(current) and current < stage_best:  # the point before this step
                stage_best, best = current, theta.detach()[0].clone()
            optimizer = _advance(value, current, theta, optimizer, best, stage.lr)
            result.iterations += 1
            now = time.perf_counter()
            seconds_per_cost = (now - t_iter) / costs[index]
            result.history.append((now - t_start, result.iterations, current))
            if keep_snapshots:
                result.snapshots.append((now - t_start, theta.detach()[0].clone()))
            if current < plateau_ref * (1 - schedule.min_improvement):
                plateau_ref, since_ref = current, 0
            else:
                since_ref += 1
            if progress is not None:
                left = (stage.iterations - it - 1) * costs[index] + sum(
                    s.iterations * c for s, c in zip(schedule.stages[index + 1:], costs[index + 1:]))
                progress({"stage_index": index, "stage_count": len(schedule.stages),
                          "iteration": result.iterations, "iterations": schedule.iterations,
                          "loss": current, "eta_seconds": left * seconds_per_cost})
            if schedule.patience is not None and since_ref >= schedule.patience:
                result.stopped = "plateau"
                break
        result.stage_seconds.append(time.perf_counter() - stage_start)
        if stage_best < math.inf and index == len(schedule.stages) - 1:
            result.loss_final = min(stage_best, loss_initial)
    if result.loss_final >= loss_initial:  # never return a point worse than the start
        best = result.theta
    result.theta = best.detach().cpu()
    result.seconds = time.perf_counter() - t_start
    return result
