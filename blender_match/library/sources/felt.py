"""Material: pressed wool felt: matted fibres, no weave, soft fuzz and slight cloudy mottling.

Structure
- Fibres: felt is wool fibres matted in every direction, so the fibre layer is four short-streak
  Anisotropic Noises, one each along 0, 90, 45 and 135 degrees (quarter turn and diagonal
  transformations with integer matrices, so they tile), combined by maximum (the topmost fibre
  wins), re-centred (histogram scan), and curled by a warp along a cloud noise (real fibres are never straight).
- Density: pressing leaves the felt denser in places: a cloud noise (Clouds 2) and a finer one
  give the mottling, in the height (thicker where denser) and in the colour.
- Pills: a few small lint balls (a Tile Generator of Gaussian bumps, scattered, most cells
  masked; the exposed pilling unmasks more) sit on the surface.
- Height: density + fibres + pills; normal from it (OpenGL) with a fine fibre detail normal;
  ambient occlusion (slight: felt is nearly flat).
- Colour: the exposed felt colour, soft-lit by the mottling (exposed) and by the fibres (the fuzz
  catches light), pills slightly lighter.
- Roughness: very high (fibres scatter), the fuzz a little rougher still. Metallic 0.

Exposed parameters
- ``felt_color`` (float3): the dyed wool colour (any).
- ``mottling``: strength of the cloudy density/colour variation.
- ``fuzz``: how much the loose surface fibres show (height and colour contrast of the fibres).
- ``pilling``: amount of small lint balls on the surface.
- ``roughness``: the felt's mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MAX,
    OUR_OCCLUSION,
    SCREEN,
    SOFT_LIGHT,
    TILES_MAX,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("felt")
    g.expose("felt_color", (0.55, 0.12, 0.12), min=0.0, max=1.0)
    g.expose("mottling", 0.45, min=0.0, max=1.0)
    g.expose("fuzz", 0.5, min=0.0, max=1.0)
    g.expose("pilling", 0.25, min=0.0, max=1.0)
    g.expose("roughness", 0.92, min=0.6, max=1.0)

    # ---- fibres in four directions ---------------------------------------------------------------
    g.add("fib_h", "anisotropic_noise", seed=81, x_amount=48, y_amount=256, smoothness=0.3)
    g.add("fib_v_src", "anisotropic_noise", seed=82, x_amount=48, y_amount=256, smoothness=0.3)
    g.add("fib_v", "transformation", {"input1": "fib_v_src"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("fib_d1_src", "anisotropic_noise", seed=83, x_amount=32, y_amount=192, smoothness=0.3)
    g.add("fib_d1", "transformation", {"input1": "fib_d1_src"}, matrix22=(1.0, 1.0, -1.0, 1.0))
    g.add("fib_d2_src", "anisotropic_noise", seed=84, x_amount=32, y_amount=192, smoothness=0.3)
    g.add("fib_d2", "transformation", {"input1": "fib_d2_src"}, matrix22=(1.0, -1.0, 1.0, 1.0))
    g.add("fib_hv", "blend", {"source": "fib_v", "destination": "fib_h"}, blendingmode=MAX, opacitymult=1.0)
    g.add("fib_dd", "blend", {"source": "fib_d2", "destination": "fib_d1"}, blendingmode=MAX, opacitymult=1.0)
    g.add("fib_all", "blend", {"source": "fib_dd", "destination": "fib_hv"}, blendingmode=MAX, opacitymult=1.0)
    g.add("curl", "clouds_1", seed=85, scale=3.0)
    g.add("fibres_curled", "warp", {"input1": "fib_all", "inputgradient": "curl"}, intensity=0.15)
    g.add("fibres", "histogram_scan", {"input_1": "fibres_curled"}, position=0.35, contrast=0.0)

    # ---- density mottling and pills ----------------------------------------------------------
    g.add("cloud_big", "clouds_2", seed=86, scale=2.0)
    g.add("cloud_small", "clouds_1", seed=87, scale=10.0)
    g.add("density", "blend", {"source": "cloud_small", "destination": "cloud_big"},
          blendingmode=SOFT_LIGHT, opacitymult=0.7)
    g.add("pills", "tile_generator", blending_mode=TILES_MAX, seed=88, x_amount=20, y_amount=20, pattern=4, scale=0.55,
          position_random=0.5, scale_random=0.6, luminance_random=0.3, mask_random=0.85)
    g.bind("pills", "mask_random", lerp(1.0, 0.6, get("pilling")).graph())

    # ---- height -----------------------------------------------------------------------------
    g.add("density_level", "histogram_range", {"input": "density"}, range=0.35, position=0.45)
    g.bind("density_level", "range", lerp(0.05, 0.4, get("mottling")).graph())
    g.add("fibred", "blend", {"source": "fibres", "destination": "density_level"},
          blendingmode=ADD_SUB, opacitymult=0.25)
    g.bind("fibred", "opacitymult", lerp(0.02, 0.2, get("fuzz")).graph())
    g.add("pilled", "blend", {"source": "pills", "destination": "fibred"}, blendingmode=MAX, opacitymult=0.75)
    g.add("height", "histogram_range", {"input": "pilled"}, range=0.9, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=1.5, inversedy=True)
    g.add("normal_fibres", "normal", {"input1": "fibres"}, intensity=0.6, inversedy=True)
    g.bind("normal_fibres", "intensity", lerp(0.05, 0.5, get("fuzz")).graph())
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_fibres"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.08, spreading=0.08,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("wool", "uniform", outputcolor=(0.55, 0.12, 0.12, 1.0))
    g.bind("wool", "outputcolor", vector(get("felt_color", 3), 1.0).graph())
    gradient_over(g, "mottled", "mottle_tone", "density", [(0.0, (0.43, 0.43, 0.43)), (1.0, (0.57, 0.57, 0.57))],
                  "wool", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("mottled", "opacitymult", lerp(0.0, 1.0, get("mottling")).graph())
    gradient_over(g, "fuzzed", "fibre_tone", "fibres", [(0.0, (0.36, 0.36, 0.36)), (1.0, (0.66, 0.66, 0.66))],
                  "mottled", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("fuzzed", "opacitymult", lerp(0.1, 1.0, get("fuzz")).graph())
    color_over(g, "pill_lit", "pill_color", (0.25, 0.25, 0.25, 1.0), "fuzzed", mask="pills", blendingmode=SCREEN,
               opacitymult=0.6)
    ao_darken(g, "basecolor", "pill_lit", floor=0.4, opacitymult=0.4, blendingmode=SOFT_LIGHT)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("roughness", "histogram_range", {"input": "fibres"}, range=0.08, position=0.92)
    g.bind("roughness", "position", get("roughness").graph())
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "fabric"

SAMPLE_RANGES = {
    "exposed.felt_color": ((0.03, 0.03, 0.03), (0.92, 0.90, 0.88)),
    "exposed.mottling": (0.1, 0.8),
    "exposed.fuzz": (0.2, 0.9),
    "exposed.pilling": (0.0, 0.6),
    "exposed.roughness": (0.85, 0.98),
    "fibres_curled.intensity": (0.05, 0.3),
    "fibres.position": (0.3, 0.45),
    "cloud_big.scale": (1.0, 4.0),
    "cloud_small.scale": (6.0, 16.0),
    "normal_main.intensity": (0.8, 2.5),
    "density.opacitymult": (0.4, 1.0),
}
