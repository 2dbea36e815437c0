"""Shared vocabulary of the material sources (``library/sources/*.py``): blend-mode names, gradient
keys, constant maps pinned so the optimiser cannot move them, and the node patterns the sources
repeat (a flat colour or a gradient map blended over a map, the ambient-occlusion darkening, the
normal and ambient occlusion of a height map)."""
from __future__ import annotations

from ..translator.runtime import SbsGraph
from ..vocabulary import ANISOTROPY, ANISOTROPY_ANGLE, AUTHORED_USAGES
from .expressions import Expr, const, get, gray4, lerp, minimum, vector

# Substance's blending-mode codes (the blend node's ``blendingmode``)
COPY, ADD, SUBTRACT, MULTIPLY, ADD_SUB, MAX, MIN, SWITCH, DIVIDE, OVERLAY, SCREEN, SOFT_LIGHT = range(12)
# the Tile Generator's own Blending Mode code for Max: the library's tile layouts were authored
# with overlapping tiles keeping the highest (Substance's default is Add)
TILES_MAX = 2
# Ambient Occlusion 2's model our graphs were authored, sampled and trained with: the three-blur
# occlusion, not the reference's construction that translated production files get (model 0;
# docs/generators.md, stop 32)
OUR_OCCLUSION = 1


def gradient_keys(stops) -> dict:
    """Gradient-map parameters from ``[(position, (r, g, b)), …]`` (opaque keys)."""
    return {"positions": [p for p, _ in stops], "colors": [c for _, rgb in stops for c in (*rgb, 1.0)]}


def constant_map(g: SbsGraph, name: str, value: float) -> str:
    """A flat grayscale map (a uniform node) whose level is bound to a constant, so it is written to
    the .sbs as a fixed value and never optimised (a dielectric's metallic 0, a metal's 1)."""
    color = (value, value, value, 1.0)
    g.add(name, "uniform", colorswitch=False, outputcolor=color)
    g.bind(name, "outputcolor", const(color).graph())
    return name


def set_material_outputs(g: SbsGraph, ambient_occlusion: str | None = None, anisotropy: bool = False):
    """Name the five material maps after the nodes of the same names (and optionally the ambient
    occlusion node; with ``anisotropy``, the anisotropy level and angle after the nodes
    ``anisotropylevel`` and ``anisotropyangle``, which ``brushing`` adds)."""
    for usage in (*AUTHORED_USAGES, *((ANISOTROPY, ANISOTROPY_ANGLE) if anisotropy else ())):
        g.set_output(usage, usage)
    if ambient_occlusion:
        g.set_output("ambientocclusion", ambient_occlusion)


def dielectric_tail(g: SbsGraph, height: str, intensity: float, relief: Expr, sheen_source: str, sheen_range: float,
                    roughness: float) -> None:
    """The tail of a one-layer dielectric: the normal node ``normal`` of ``height`` (OpenGL,
    authored ``intensity``) bound to the expression ``relief``; the roughness a narrow histogram
    range (``sheen_range`` wide, node ``rough``) of ``sheen_source`` centred on the exposed
    ``roughness`` (authored ``roughness``), passed to the node ``roughness``; metallic 0; the five
    material outputs named."""
    g.add("normal", "normal", {"input1": height}, intensity=intensity, inversedy=True)
    g.bind("normal", "intensity", relief.graph())
    g.add("rough", "histogram_range", {"input": sheen_source}, range=sheen_range, position=roughness)
    g.bind("rough", "position", get("roughness").graph())
    g.add("roughness", "passthrough", {"input": "rough"})
    constant_map(g, "metallic", 0.0)
    set_material_outputs(g)


def brushing(g: SbsGraph, level: Expr, angle: float) -> None:
    """The anisotropic highlight of a brushed metal: the level map (``ANISOTROPY``) a flat grey
    bound to ``level``, an expression of exposed parameters (so the fit moves it), and the angle
    map (``ANISOTROPY_ANGLE``) pinned to ``angle``, the direction of the brushing streaks in turns
    counter-clockwise from +u (a graph's streaks do not turn with a parameter)."""
    g.add(ANISOTROPY, "uniform", colorswitch=False)
    g.bind(ANISOTROPY, "outputcolor", gray4(level).graph())
    constant_map(g, ANISOTROPY_ANGLE, angle)


def color_over(g: SbsGraph, name: str, color_name: str, color, destination: str, mask: str | None = None,
               **blend) -> str:
    """A flat colour (the uniform node ``color_name``, ``outputcolor=color``) blended over
    ``destination`` through the opacity ``mask`` (None: everywhere) by the blend node ``name``
    (``blend``: its parameters, e.g. ``blendingmode``, ``opacitymult``)."""
    g.add(color_name, "uniform", outputcolor=color)
    inputs = {"source": color_name, "destination": destination}
    if mask is not None:
        inputs["opacity"] = mask
    g.add(name, "blend", inputs, **blend)
    return name


def gradient_over(g: SbsGraph, name: str, tones_name: str, source: str, stops, destination: str,
                  mask: str | None = None, **blend) -> str:
    """A gradient map ``tones_name`` of ``source`` (``stops`` as in ``gradient_keys``) blended over
    ``destination`` through the opacity ``mask`` (None: everywhere) by the blend node ``name``: the
    mottling of a colour by a noise (usually SOFT_LIGHT)."""
    g.add(tones_name, "gradient", {"input1": source}, **gradient_keys(stops))
    inputs = {"source": tones_name, "destination": destination}
    if mask is not None:
        inputs["opacity"] = mask
    g.add(name, "blend", inputs, **blend)
    return name


# what the dust of ``dust_specks`` looks like where it lies on a coat: a light grey laid over the
# base colour at this opacity, this roughness (a matte speck on a glossy coat), and this share of
# the mask added to the height (a hair above the coat)
DUST_COLOR = (0.72, 0.71, 0.68, 1.0)
DUST_OPACITY = 0.85
DUST_ROUGHNESS = (0.85, 0.85, 0.85, 1.0)
DUST_RELIEF = 0.08


def dust_specks(g: SbsGraph, amount: Expr, seeds: tuple[int, int]) -> str:
    """Dust on a smooth coat: sparse white-noise dots, slightly blurred, plus a few larger lint
    specks (a thresholded spot noise), both more numerous with the expression ``amount`` (0 none,
    1 a dusty surface); returns the name of their mask, ``dust_mask`` (nodes ``dust_noise``,
    ``dust_dots``, ``dust_soft``, ``lint_noise``, ``lint``; ``seeds``: the two noises')."""
    g.add("dust_noise", "white_noise", seed=seeds[0])
    g.add("dust_dots", "histogram_scan", {"input_1": "dust_noise"}, contrast=0.9)
    g.bind("dust_dots", "position", lerp(0.0, 0.005, amount).graph())
    g.add("dust_soft", "blur", {"input1": "dust_dots"}, intensity=0.6)
    g.add("lint_noise", "gaussian_spots_1", seed=seeds[1], scale=8.0)
    g.add("lint", "histogram_scan", {"input_1": "lint_noise"}, contrast=0.85)
    g.bind("lint", "position", lerp(0.0, 0.004, amount).graph())
    g.add("dust_mask", "blend", {"source": "lint", "destination": "dust_soft"}, blendingmode=ADD, opacitymult=0.8)
    return "dust_mask"


def grain_tones(g: SbsGraph, prefix: str, color: Expr, mask: str, dark: float, light: float, dark_rgb,
                light_rgb) -> str:
    """A wood's two tones picked by its grain: the uniform nodes ``{prefix}_dark`` (``color`` x
    ``dark``) and ``{prefix}_light`` (``color`` x ``light``, clamped to 1; authored values
    ``dark_rgb`` and ``light_rgb``), the light one blended over the dark one through ``mask`` by
    the node ``{prefix}_base`` (returned)."""
    g.add(f"{prefix}_dark", "uniform", outputcolor=(*dark_rgb, 1.0))
    g.bind(f"{prefix}_dark", "outputcolor", vector(color * dark, 1.0).graph())
    g.add(f"{prefix}_light", "uniform", outputcolor=(*light_rgb, 1.0))
    g.bind(f"{prefix}_light", "outputcolor", vector(minimum(color * light, const((1.0, 1.0, 1.0))), 1.0).graph())
    g.add(f"{prefix}_base", "blend", {"source": f"{prefix}_light", "destination": f"{prefix}_dark", "opacity": mask},
          blendingmode=COPY, opacitymult=1.0)
    return f"{prefix}_base"


def ao_darken(g: SbsGraph, name: str, destination: str, floor: float, opacitymult: float,
              blendingmode: int = MULTIPLY, ao: str = "ao", color_name: str = "ao_color") -> str:
    """Darken ``destination`` in the crevices: the ambient occlusion ``ao`` mapped to a grey ramp
    from ``floor`` to white (the gradient node ``color_name``), blended by the node ``name``."""
    g.add(color_name, "gradient", {"input1": ao},
          **gradient_keys([(0.0, (floor, floor, floor)), (1.0, (1.0, 1.0, 1.0))]))
    g.add(name, "blend", {"source": color_name, "destination": destination},
          blendingmode=blendingmode, opacitymult=opacitymult)
    return name


def normal_and_ao(g: SbsGraph, height: str, intensity: float, height_depth: float, spreading: float,
                  normal: str = "normal", ao: str = "ao") -> str:
    """The tail of a height map: the normal node ``normal`` (OpenGL, ``intensity``) and the ambient
    occlusion node ``ao`` (``height_depth``, ``spreading``), both from ``height``. Returns ``normal``."""
    g.add(normal, "normal", {"input1": height}, intensity=intensity, inversedy=True)
    g.add(ao, "ambient_occlusion_2", {"source": height}, height_depth=height_depth, spreading=spreading,
          model=OUR_OCCLUSION)
    return normal


def fold(g: SbsGraph, src: str, i: int) -> str:
    """|2x - 1| of ``src`` from histogram scans (max(0, 2x-1) and max(0, 1-2x), blended by max), as
    the nodes ``fold{i}_inv``, ``fold{i}_hi``, ``fold{i}_lo`` and ``fold{i}``: each fold doubles the
    number of periods of a distance field (growth rings)."""
    g.add(f"fold{i}_inv", "invert_grayscale", {"source": src})
    g.add(f"fold{i}_hi", "histogram_scan", {"input_1": src}, position=0.25, contrast=0.0)
    g.add(f"fold{i}_lo", "histogram_scan", {"input_1": f"fold{i}_inv"}, position=0.25, contrast=0.0)
    g.add(f"fold{i}", "blend", {"source": f"fold{i}_lo", "destination": f"fold{i}_hi"},
          blendingmode=MAX, opacitymult=1.0)
    return f"fold{i}"


def keys_near(stops, d: float) -> tuple:
    """A tight (lo, hi) sampling range around a gradient's key colours (each channel +- d, alpha
    kept at 1), for ``SAMPLE_RANGES``: the sampler draws each channel independently, and a wide
    range would tint the tones."""
    lo = [c for _, rgb in stops for c in (*(max(0.0, v - d) for v in rgb), 1.0)]
    hi = [c for _, rgb in stops for c in (*(min(1.0, v + d) for v in rgb), 1.0)]
    return lo, hi


def rgba_near(rgb, d: float) -> tuple:
    """A (lo, hi) sampling range around a flat colour (each channel +- d, alpha 1)."""
    return [max(0.0, v - d) for v in rgb] + [1.0], [min(1.0, v + d) for v in rgb] + [1.0]


def pinned_keys(stops) -> dict:
    """A gradient's keys pinned in ``SAMPLE_RANGES`` (sampling them channel by channel would tint
    a neutral key): the ranges of its ``positions`` and ``colors``, each (value, value)."""
    keys = gradient_keys(stops)
    return {"positions": (keys["positions"], keys["positions"]), "colors": (keys["colors"], keys["colors"])}
