"""Targets of ``bench accuracy``: synthetic photos with a ground truth, real photos, and stress
photos that no graph expresses or that push the pipeline to its edges.

- synthetic: a library graph with ``sample_params(graph, k)`` for k >= 900 (indices no method is
  trained or tuned on) rendered with graph noise seed ``TRUTH_SEED`` (1234; fits use seed 0, so no
  pixel alignment is possible), truth kept (parameters, maps);
- real: the flash photos in shared/data/photos, each fitted with the graph of its family;
- stress (descriptor loss only, unless noted): ``black``, ``white``, ``saturated`` (pure red),
  ``noise`` (uniform RGB noise), ``tiny`` (32x32: ``load_photo`` refuses it cleanly),
  ``nonsquare`` (2048x160 stripes: the loader keeps the centred square), ``checker_text`` (a
  checkerboard with text, a pattern no generator makes), ``object`` (a synthetic target with a
  blue disc pasted on it: the truth is the material under it), ``wrong_family`` (the bricks graph
  fitted to the real wood photo).
Stress photos (but ``object``, pasted on the render itself) are written as PNG files and read back
by ``load_photo``, so the loader is part of what is tested.
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import torch
from PIL import Image, ImageDraw

from ..errors import OptionError
from ..library import apply_params, load_library_graph, sample_params
from ..photo import PhotoError, load_photo
from .accuracy_metrics import Truth, make_truth

TRUTH_SEED = 1234
STRESS_KINDS = ("black", "white", "saturated", "noise", "tiny", "nonsquare", "checker_text", "object",
                "wrong_family")
REAL_GRAPHS = {"asphalt": "asphalt", "leather": "leather", "plaster": "plaster", "wood": "raw_wood",
               "brick": "bricks", "marble": "marble", "concrete": "concrete", "fabric": "woven_fabric",
               "metal": "brushed_metal", "stone": "rough_stone", "tile": "ceramic_tiles", "ground": "ground"}


@dataclass
class Target:
    """A photo to fit with ``graph``: ``name`` is unique in a run; ``group`` is "main", "seeds" or
    "stress"; ``photo`` is None when the loader refused it (``refusal`` says why)."""

    name: str
    group: str
    kind: str
    graph: str
    photo: torch.Tensor | None
    truth: Truth | None = None
    refusal: str | None = None


def photos_dir() -> Path:
    shared = os.environ.get("BLENDER_MATCH_SHARED")
    root = Path(shared) if shared else Path(__file__).resolve().parents[2].parent / "shared"
    return root / "data" / "photos"


def real_photos(names=None) -> list[Path]:
    """The real photos (``names``: keep those whose file name contains one of them)."""
    folder = photos_dir()
    paths = sorted(folder.glob("*.png")) if folder.is_dir() else []
    if names is not None:
        paths = [p for p in paths if any(n in p.stem for n in names)]
    return paths


def graph_for_photo(path: Path, known: list[str]) -> str | None:
    for word, graph in REAL_GRAPHS.items():
        if word in path.stem and graph in known:
            return graph
    return None


def synthetic(name: str, k: int, size: int, group: str = "main", seed: int = TRUTH_SEED) -> Target:
    """Library graph ``name`` at its k-th sampled variant, rendered at ``size`` px."""
    truth_graph = load_library_graph(name)
    apply_params(truth_graph, sample_params(name, k))
    photo, truth = make_truth(truth_graph, truth_graph.get_vector(), size, seed)
    return Target(f"{name}/{k}", group, "synthetic", name, photo, truth)


def real(path: Path, graph: str, size: int, group: str = "main", kind: str = "real") -> Target:
    return Target(f"real:{path.stem}", group, kind, graph, load_photo(path, size))


def _save(folder: Path, name: str, pixels: np.ndarray) -> Path:
    path = folder / f"{name}.png"
    Image.fromarray(np.clip(np.rint(pixels * 255), 0, 255).astype(np.uint8)).save(path)
    return path


def _checker_text(side: int = 512) -> np.ndarray:
    cells = (np.indices((side, side)) // (side // 8)).sum(axis=0) % 2
    img = Image.fromarray((cells * 180 + 40).astype(np.uint8)).convert("RGB")
    draw = ImageDraw.Draw(img)
    for row in range(6):
        draw.text((20, 20 + row * 80), "MATCH 0123 ABC xyz", fill=(220, 30, 30))
    return np.asarray(img, dtype=np.float32) / 255


def _with_disc(photo: torch.Tensor) -> np.ndarray:
    image = photo[0].permute(1, 2, 0).cpu().numpy().copy()
    side = image.shape[0]
    yy, xx = np.indices((side, side))
    disc = (yy - side * 0.45) ** 2 + (xx - side * 0.55) ** 2 < (side * 0.2) ** 2
    image[disc] = (0.1, 0.25, 0.8)
    return image


def stress(kind: str, graph: str, size: int, k: int = 901) -> Target:
    """One stress target fitted with ``graph`` (``wrong_family``: bricks on the real wood photo)."""
    if kind == "wrong_family":
        wood = real_photos(("wood",))
        if not wood:
            raise FileNotFoundError(f"no real wood photo under {photos_dir()}")
        target = real(wood[0], "bricks", size, group="stress", kind="wrong_family")
        return replace(target, name="stress:wrong_family")
    if kind == "object":  # the truth's render with a disc on it (a tensor: the loader adds nothing)
        base = synthetic(graph, k, size)
        assert base.photo is not None  # a synthetic target always has its render
        photo = torch.from_numpy(_with_disc(base.photo)).permute(2, 0, 1)[None].float()
        return Target(f"stress:{kind}", "stress", kind, graph, photo, base.truth)
    rng = np.random.default_rng(5)
    if kind == "black":
        pixels = np.zeros((512, 512, 3))
    elif kind == "white":
        pixels = np.ones((512, 512, 3))
    elif kind == "saturated":
        pixels = np.zeros((512, 512, 3))
        pixels[..., 0] = 1.0
    elif kind == "noise":
        pixels = rng.random((512, 512, 3))
    elif kind == "tiny":
        pixels = rng.random((32, 32, 3))
    elif kind == "nonsquare":
        pixels = np.broadcast_to((np.sin(np.arange(2048) / 9.0) * 0.4 + 0.5)[None, :, None], (160, 2048, 3))
    elif kind == "checker_text":
        pixels = _checker_text()
    else:
        raise OptionError(f"unknown stress target {kind!r} (kinds: {', '.join(STRESS_KINDS)})")
    with tempfile.TemporaryDirectory() as tmp:
        path = _save(Path(tmp), kind, pixels)
        try:
            photo = load_photo(path, size)
        except PhotoError as exc:
            return Target(f"stress:{kind}", "stress", kind, graph, None, refusal=str(exc).replace(tmp, "<tmp>"))
    return Target(f"stress:{kind}", "stress", kind, graph, photo)
