"""Accuracy metrics of ``blender-match bench accuracy``: how close a fitted parameter vector comes
to a target, how a run is classified (success / degraded / failed), and the Pareto front of
(time, error) points.

Scores of a synthetic target (``Truth`` known: parameters, maps, noise seed):
- ``descriptor_loss``: the paper's loss, the L1 distance of the texture descriptors (Gram
  matrices at the paper's 512/256/128 scales, capped at the evaluation size) between the flash
  render of the candidate and the target photo;
- ``param_error``: mean absolute difference of the normalised parameter vectors;
- ``map_rmse``: RMSE of each material map against the truth's, the candidate's maps rendered with
  the *truth's* noise seed (a fit uses another seed, so its own maps are not pixel-aligned with the
  truth's even for perfect parameters);
- ``novel_rmse``: RMSE of the sRGB renders of those maps and of the truth's under a light moved away
  from the camera (``NOVEL_LIGHT``), where a wrong roughness, normal or metallic shows.
The candidate is rendered once, with the truth's seed, for all four. A real photo has no truth:
its render uses the fit's seed and only the descriptor loss is scored.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from ..diffmat.descriptor import style_loss
from ..diffmat.optim import resize_square
from ..diffmat.render import render_maps
from ..vocabulary import AUTHORED_USAGES

NOVEL_LIGHT = (0.5, 0.25)  # light offset from the camera, in sample widths (x right, y up)
LOSS_TOLERANCE = 0.01  # a final loss above the start's by more than this fraction: failed
DEGRADED_GAIN = 0.10  # a loss reduced by less than this fraction: degraded

CLASSIFICATION_RULE = (
    "**refused**: the photo was turned down cleanly at load (PhotoError), nothing ran. "
    "**failed**: any other exception, a NaN/inf loss or parameter, or a final descriptor loss more than "
    f"{LOSS_TOLERANCE:.0%} above the loss at the method's own start (default parameters, or the prediction). "
    f"**degraded**: the loss fell by less than {DEGRADED_GAIN:.0%} from that start, or (synthetic targets) the "
    "parameter error is larger than the default parameters'. **success**: otherwise.")


@dataclass
class Truth:
    """The ground truth of a synthetic target: normalised parameters, maps rendered with ``seed``
    and their render under ``NOVEL_LIGHT``."""

    theta: torch.Tensor
    maps: dict[str, torch.Tensor]
    novel: torch.Tensor
    seed: int


def make_truth(graph, theta: torch.Tensor, size: int, seed: int) -> tuple[torch.Tensor, Truth]:
    """Render ``graph`` at ``theta`` (P,) with noise ``seed``: the target photo and its truth."""
    with torch.no_grad():
        maps = graph(size=size, seed=seed, theta=theta.reshape(1, -1))
        photo = render_maps(maps)
        novel = render_maps(maps, light_offset=NOVEL_LIGHT)
    kept = {k: v.detach() for k, v in maps.items() if k in AUTHORED_USAGES}
    return photo[:1].detach(), Truth(theta.detach().reshape(-1).cpu(), kept, novel[:1].detach(), seed)


def image_rmse(a: torch.Tensor, b: torch.Tensor) -> float:
    return float(((a.float() - b.float()) ** 2).mean().sqrt())


def map_rmse(maps: dict[str, torch.Tensor], truth: dict[str, torch.Tensor]) -> dict[str, float]:
    """RMSE of each map both dictionaries hold (a colour map's RGB, a gray map's one channel)."""
    out = {}
    for name in AUTHORED_USAGES:
        if name in maps and name in truth:
            a, b = maps[name][:1], truth[name][:1]
            channels = min(a.shape[1], b.shape[1], 3)
            out[name] = image_rmse(a[:, :channels], b[:, :channels])
    return out


def param_error(theta: torch.Tensor, truth: torch.Tensor) -> float:
    """Mean absolute difference in the graph's normalised parameter space."""
    return float((theta.detach().reshape(-1).cpu().float() - truth.reshape(-1).float()).abs().mean())


def scales_for(size: int) -> tuple[int, ...]:
    """The paper's descriptor scales (512/256/128), capped at ``size``."""
    return cap_scales((512, 256, 128), size)


def cap_scales(scales: tuple[int, ...], cap: int) -> tuple[int, ...]:
    return tuple(sorted({min(s, cap) for s in scales}, reverse=True))


class Scorer:
    """Scores candidate parameter vectors of one graph against one target photo."""

    def __init__(self, descriptor, photo: torch.Tensor, size: int, truth: Truth | None = None, fit_seed: int = 0):
        self.descriptor = descriptor
        self.size = size
        self.scales = scales_for(size)
        self.truth = truth
        self.fit_seed = fit_seed
        with torch.no_grad():
            self.target = descriptor(resize_square(photo, size), self.scales)

    def score(self, graph, theta: torch.Tensor, seed: int | None = None) -> dict:
        """{"descriptor_loss", and with a truth "param_error", "map_rmse" {name: rmse},
        "map_rmse_mean", "novel_rmse"}; ``seed`` overrides the render's noise seed."""
        if seed is None:
            seed = self.truth.seed if self.truth is not None else self.fit_seed
        device = self.target.device
        with torch.no_grad():
            maps = graph(size=self.size, seed=seed, theta=theta.reshape(1, -1).to(device))
            image = render_maps(maps)[:1]
            descriptor_loss = float(style_loss(self.descriptor(image, self.scales), self.target)[0])
            out: dict[str, float | dict[str, float]] = {"descriptor_loss": descriptor_loss}
            if self.truth is not None:
                rmse = map_rmse(maps, self.truth.maps)
                out["param_error"] = param_error(theta, self.truth.theta)
                out["map_rmse"] = rmse
                out["map_rmse_mean"] = sum(rmse.values()) / len(rmse) if rmse else math.nan
                out["novel_rmse"] = image_rmse(render_maps(maps, light_offset=NOVEL_LIGHT)[:1], self.truth.novel)
        return out


def finite(*values) -> bool:
    """Whether every number (or tensor, or dict of numbers) given is finite (None is ignored)."""
    for v in values:
        if v is None:
            continue
        if isinstance(v, dict):
            if not finite(*v.values()):
                return False
        elif isinstance(v, torch.Tensor):
            if not bool(torch.isfinite(v).all()):
                return False
        elif not math.isfinite(float(v)):
            return False
    return True


def classify(*, loss_start: float | None, loss_final: float | None, error: str | None = None,
             refused: bool = False, theta_finite: bool = True, param_error: float | None = None,
             param_error_default: float | None = None) -> str:
    """"refused", "failed", "degraded" or "success" by ``CLASSIFICATION_RULE``."""
    if refused:
        return "refused"
    if error is not None or not theta_finite or loss_start is None or loss_final is None:
        return "failed"
    if not finite(loss_start, loss_final, param_error):
        return "failed"
    if loss_final > loss_start * (1 + LOSS_TOLERANCE):
        return "failed"
    if loss_final > loss_start * (1 - DEGRADED_GAIN):
        return "degraded"
    if param_error is not None and param_error_default is not None and param_error > param_error_default:
        return "degraded"
    return "success"


def pareto_front(points) -> list[int]:
    """Indices of the points (x, y) no other point beats in both (lower is better in each; a
    point with a NaN is never on the front), ordered by x."""
    good = [(i, float(x), float(y)) for i, (x, y) in enumerate(points)
            if x is not None and y is not None and math.isfinite(float(x)) and math.isfinite(float(y))]
    good.sort(key=lambda p: (p[1], p[2]))
    front, best_y = [], math.inf
    for i, _, y in good:
        if y < best_y:
            front.append(i)
            best_y = y
    return front
