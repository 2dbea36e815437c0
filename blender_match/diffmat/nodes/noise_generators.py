"""Declarations of Substance's noise generators (see functional/noise_generators.py).

Recipe-based generators share one parameter set: ``scale`` (continuous: a fractional scale blends
the two neighbouring integer lattice frequencies), ``disorder`` (phase shift of the random lattice,
period 1), plus ``roughness`` for the fractal sums and ``balance`` / ``contrast`` for the grunge
maps. Substance has ``scale`` as an integer slider on most noises; it is declared continuous here so
that it can be optimised, and an integer value gives exactly the integer frequency.
"""
from .. import functional as F
from ..functional.noise_generators import MAX_LATTICE, NOISE_RECIPES
from .registry import register
from .spec import NodeSpec, Param

CONTEXT = ("size", "seed", "device", "dtype")


def recipe_params(recipe, scale_range, extra) -> tuple:
    lo, hi, default = scale_range
    params = [Param("scale", float(default), float(lo), float(hi),
                    doc="lattice frequency multiplier (fractional values blend neighbouring integers)"),
              Param("disorder", 0.0, 0.0, 1.0, doc="phase shift of the random lattice (period 1)")]
    if "roughness" in extra:
        params.append(Param("roughness", recipe.roughness, 0.0, 1.0, doc="weight ratio of successive octaves"))
    if "balance" in extra:
        params.append(Param("balance", 0.5, 0.0, 1.0, doc="brightness offset of the tone curve"))
    if "contrast" in extra:
        params.append(Param("contrast", 0.5, 0.0, 1.0, doc="steepness of the tone curve"))
    if "invert" in extra:
        params.append(Param("invert", False, kind="bool", doc="1 - the map"))
    return tuple(params)


def register_recipes(table: dict):
    for name, (recipe, scale_range, extra) in table.items():
        register(NodeSpec(name, "generator", getattr(F, f"noise_{name}"),
                          params=recipe_params(recipe, scale_range, extra), context=CONTEXT,
                          doc=f"{name}: noise generator (recipe {recipe})."))


register_recipes(NOISE_RECIPES)

register(NodeSpec("white_noise", "generator", F.noise_white, context=CONTEXT,
                  doc="White Noise: a uniform random value per texel of a 512 x 512 texture-space lattice."))
register(NodeSpec("white_noise_fast", "generator", F.noise_white_fast, context=CONTEXT,
                  doc="White Noise Fast: a uniform random value per texel of a 256 x 256 lattice."))
register(NodeSpec("blue_noise_fast", "generator", F.noise_blue_fast, context=CONTEXT,
                  doc="Blue Noise Fast: high-passed white noise on a 256 x 256 lattice."))
register(NodeSpec(
    "fractal_sum_base", "generator", F.noise_fractal_sum_base,
    params=(Param("roughness", 0.5, 0.0, 1.0, doc="weight ratio of successive levels"),
            Param("min_level", 1, 0, 10, kind="int", doc="coarsest level (2^L cells)"),
            Param("max_level", 8, 0, 10, kind="int", doc="finest level (2^L cells)")),
    context=CONTEXT, doc="Fractal Sum Base: a sum of value-noise levels 2^min_level .. 2^max_level cells."))
register(NodeSpec(
    "anisotropic_noise", "generator", F.noise_anisotropic,
    params=(Param("x_amount", 8, 1, MAX_LATTICE, kind="int", doc="lattice cells across"),
            Param("y_amount", 128, 1, MAX_LATTICE, kind="int", doc="lattice cells down"),
            Param("smoothness", 0.5, 0.0, 1.0, doc="hard bands (0) to smooth interpolation down (1)"),
            Param("interpolation", True, kind="bool", doc="cubic (on) or linear (off) interpolation"),
            Param("rotate", False, kind="bool", doc="a quarter turn: vertical streaks"),
            Param("y_amount_by_resolution", False, kind="bool",
                  doc="y_amount replaced by one row a pixel at 512 px (RESOLUTION_ROWS)")),
    context=CONTEXT, doc="Anisotropic Noise: streaks from a stretched random lattice."))
