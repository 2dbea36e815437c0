"""What a match is asked to do (``MatchOptions``), the checks of those options, and the one place a
quality name becomes the optimiser's ``Schedule``."""
from __future__ import annotations

from dataclasses import dataclass

from ..diffmat.calibration import ZOOM_RANGE
from ..diffmat.optim import Schedule, quality_schedule
from ..errors import OptionError
from ..vocabulary import DEFAULT_DEVICE, DEFAULT_QUALITY, QUALITY_NAMES

PHOTO_SIZE = 512  # the photo is described at 512 at most (the paper's largest scale)
# Automatic selection fits this many of the best-ranked graphs and keeps the best final loss. The
# paper fits 3; on real photos the ranking's first is the better choice (docs/benchmarks.md): the
# fit's loss favours the graphs that absorb a photo's lighting, not the ones that share its material.
AUTO_CANDIDATES = 1
MIN_SIZE, MAX_SIZE = 16, 8192


@dataclass
class MatchOptions:
    """What to match and how. ``graph``: a library graph's name, a bundled graph's name or a
    ``.sbs`` path (None: automatic selection). ``iterations`` overrides the quality preset's
    iteration count (tests and scripted drafts). ``candidates``: how many of the best-ranked graphs
    automatic selection fits, keeping the best final loss (3: the paper's). ``calibrate``: solve the
    photo's exposure and white balance as a gain on the base colour, at the fit's start and after
    it (``diffmat.calibration``).
    ``zoom``: texture periods across the photo, fixed for the fit (1, the default: the graph's
    authored scale); None searches it (``diffmat.zoom_search``; not the default: on the 33
    development photos it helped as many fits as it hurt, docs/benchmarks.md). ``lighting``: fit
    under the photo's flash falloff (its beam pattern and vignetting,
    ``calibration.solve_lighting``) instead of the ideal flash."""

    graph: str | None = None
    size: int = 2048
    quality: str = DEFAULT_QUALITY
    seed: int = 0
    device: str = DEFAULT_DEVICE
    overwrite: bool = False
    iterations: int | None = None
    candidates: int = AUTO_CANDIDATES
    calibrate: bool = True
    zoom: float | None = 1.0
    lighting: bool = True


def check_size(size) -> int:
    """``size`` when it is a power of two between MIN_SIZE and MAX_SIZE, else OptionError."""
    if (isinstance(size, bool) or not isinstance(size, int) or size < MIN_SIZE or size > MAX_SIZE
            or size & (size - 1)):
        raise OptionError(f"size {size!r}: expected a power of two between {MIN_SIZE} and {MAX_SIZE}")
    return size


def check_candidates(candidates) -> int:
    """``candidates`` when it is a positive whole number, else OptionError."""
    if isinstance(candidates, bool) or not isinstance(candidates, int) or candidates < 1:
        raise OptionError(f"candidates {candidates!r}: expected a positive integer")
    return candidates


def check_zoom(zoom) -> float | None:
    """``zoom`` when it is None (searched) or a number within the calibration's ``ZOOM_RANGE``, else OptionError."""
    if zoom is None:
        return None
    if isinstance(zoom, bool) or not isinstance(zoom, (int, float)) or not ZOOM_RANGE[0] <= zoom <= ZOOM_RANGE[1]:
        raise OptionError(f"zoom {zoom!r}: expected a number of texture periods across the photo between "
                          f"{ZOOM_RANGE[0]:g} and {ZOOM_RANGE[1]:g}")
    return float(zoom)


def match_schedule(quality: str, iterations: int | None = None) -> Schedule:
    """The optimiser's schedule for a quality name, rescaled to ``iterations`` in all when given."""
    if quality not in QUALITY_NAMES:
        raise OptionError(f"quality {quality!r}: expected one of {', '.join(QUALITY_NAMES)}")
    if iterations is not None and (isinstance(iterations, bool) or not isinstance(iterations, int)
                                   or iterations < 1):
        raise OptionError(f"iterations {iterations!r}: expected a positive integer")
    return quality_schedule(quality, iterations)
