"""Yardstick distances between a photo and a render that no fit minimises (numpy only).

- ``patch_distance``: a sliced Wasserstein distance between the multi-scale distributions of 7x7
  RGB patches of the two images. Both are resized to 256², split into a Laplacian pyramid of 4
  levels (3 band-pass levels and the low-pass rest), and at each level the patches of both images
  are normalised by the *photo's* patch statistics (mean patch, one standard deviation), projected
  on fixed random unit directions and compared as sorted samples (the 1-D Wasserstein-2 distance of
  each projection). The result is the root mean square over projections and levels, times 100. It
  sees structure at every scale (speckle, grain, cracks, blobs) and its contrast, and is blind to
  where things are, so renders with another noise seed compare fairly.
- ``colour_distance``: per-channel mean and standard deviation of the sRGB pixels, the Euclidean
  distance between the two 6-vectors, times 100.

Images are (H, W, 3) numpy arrays or (1, 3, H, W) tensors in [0, 1] (sRGB, as a photo is); a
non-square image is cropped to its centred square. The random directions and patch samples come
from a fixed seed, so the same pair of images always gives the same figure.
"""
from __future__ import annotations

import numpy as np

SIDE = 256
LEVELS = 4
PATCH = 7
PROJECTIONS = 64
SAMPLES = 8192
SEED = 20201


def as_array(image) -> np.ndarray:
    """An (H, W, 3) float64 array of ``image`` ((H, W, 3) array or (1, 3, H, W) tensor), its centred
    square."""
    if hasattr(image, "detach"):
        image = image.detach().float().cpu().numpy()
        if image.ndim == 4:
            image = image[0]
        image = np.transpose(image, (1, 2, 0))
    image = np.asarray(image, dtype=np.float64)
    if image.ndim != 3 or image.shape[2] < 3:
        raise ValueError(f"expected an (H, W, 3) image, got shape {image.shape}")
    h, w = image.shape[:2]
    side = min(h, w)
    top, left = (h - side) // 2, (w - side) // 2
    return image[top:top + side, left:left + side, :3]


def resize(image: np.ndarray, side: int = SIDE) -> np.ndarray:
    """Box-filtered resize of a square (S, S, C) image to ``side`` (block means when S is a
    multiple of ``side``, else area weights)."""
    size = image.shape[0]
    if size == side:
        return image
    if size % side == 0:
        f = size // side
        return image.reshape(side, f, side, f, -1).mean(axis=(1, 3))
    weights = _area_weights(size, side)
    rows = np.einsum("ij,jkc->ikc", weights, image)  # one axis at a time: a single three-operand
    return np.einsum("ikc,lk->ilc", rows, weights)  # einsum would loop over all four indices at once


def _area_weights(size: int, side: int) -> np.ndarray:
    """(side, size) matrix averaging the source pixels each target pixel covers."""
    edges = np.linspace(0, size, side + 1)
    lo, hi = edges[:-1, None], edges[1:, None]
    pixels = np.arange(size)[None, :]
    overlap = np.clip(np.minimum(hi, pixels + 1) - np.maximum(lo, pixels), 0, None)
    return overlap / overlap.sum(axis=1, keepdims=True)


_BINOMIAL = np.array([1, 4, 6, 4, 1], dtype=np.float64) / 16


def _blur(image: np.ndarray) -> np.ndarray:
    """Separable 5-tap binomial blur with reflected borders (photos do not tile)."""
    for axis in (0, 1):
        padded = np.pad(image, [(2, 2) if a == axis else (0, 0) for a in range(3)], mode="reflect")
        n = image.shape[axis]
        image = sum(w * np.take(padded, np.arange(i, i + n), axis=axis) for i, w in enumerate(_BINOMIAL))
    return image


def laplacian_pyramid(image: np.ndarray, levels: int = LEVELS) -> list[np.ndarray]:
    """``levels`` images: ``levels - 1`` band-pass levels, finest first, then the low-pass rest."""
    out = []
    current = image
    for _ in range(levels - 1):
        low = _blur(current)[::2, ::2]
        up = np.repeat(np.repeat(low, 2, axis=0), 2, axis=1)
        out.append(current - _blur(up))
        current = low
    out.append(current)
    return out


def _patches(level: np.ndarray, pick: np.ndarray | None) -> np.ndarray:
    """The 7x7xC patches of ``level`` (those at the flat indices ``pick``, when given): (N, 49 C)."""
    c = level.shape[2]
    # numpy's stubs type ``axis`` as one index; a tuple of axes is documented and works
    windows = np.lib.stride_tricks.sliding_window_view(level, (PATCH, PATCH), axis=(0, 1))  # type: ignore[call-overload]
    flat = windows.reshape(-1, c * PATCH * PATCH)
    return flat if pick is None else flat[pick]


def patch_distance(photo, render, *, side: int = SIDE, levels: int = LEVELS, projections: int = PROJECTIONS,
                   samples: int = SAMPLES) -> float:
    """Sliced Wasserstein distance of the multi-scale 7x7 patch distributions (module docstring)."""
    a, b = (laplacian_pyramid(resize(as_array(x), side), levels) for x in (photo, render))
    rng = np.random.default_rng(SEED)
    total = 0.0
    for level_a, level_b in zip(a, b):
        count = (level_a.shape[0] - PATCH + 1) * (level_a.shape[1] - PATCH + 1)
        pick = rng.choice(count, samples, replace=False) if count > samples else None  # same places in both
        pa, pb = _patches(level_a, pick), _patches(level_b, pick)
        mean = pa.mean(axis=0)
        scale = max(float((pa - mean).std()), 1e-3)
        directions = rng.standard_normal((pa.shape[1], projections))
        directions /= np.linalg.norm(directions, axis=0, keepdims=True)
        qa = np.sort((pa - mean) / scale @ directions, axis=0)
        qb = np.sort((pb - mean) / scale @ directions, axis=0)
        total += float(((qa - qb) ** 2).mean())
    return 100.0 * float(np.sqrt(total / len(a)))


def colour_stats(image) -> np.ndarray:
    """Per-channel mean then per-channel standard deviation: a 6-vector."""
    pixels = as_array(image).reshape(-1, 3)
    return np.concatenate([pixels.mean(axis=0), pixels.std(axis=0)])


def colour_distance(photo, render) -> float:
    """Euclidean distance of the two images' colour statistics (module docstring), times 100."""
    return 100.0 * float(np.linalg.norm(colour_stats(photo) - colour_stats(render)))
