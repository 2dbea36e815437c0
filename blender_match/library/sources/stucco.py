"""Stucco: a painted knock-down stucco wall, flattened irregular splats with slightly raised edges.

Structure
- Splats: two Perlin noises of different sizes, summed and frayed by a fine noise, thresholded
  (histogram scan) into irregular islands; how much of the wall they cover is the exposed
  coverage. The trowel knocked them flat: the islands are plateaus (the mask softened by a small
  blur), not domes.
- Raised edges: where the trowel pushed the plaster outwards, a narrow band just inside each
  splat's border (a histogram select of the blurred mask) rises a little above the plateau.
- Base coat: between the splats the sprayed under-coat shows, lower and with a fine sandy
  orange-peel texture (BnW Spots 3 + a fine Perlin); the plateaus keep only a faint version of it
  (smoothed by the trowel).
- Colour: one paint colour (white by default), the hollows a little darker (paint pools, dirt,
  occlusion), plateau tops a touch lighter, with a very soft large-scale mottling.
- Roughness: matte paint around the exposed value; plateaus slightly smoother than the hollows.
- Normal from the height (OpenGL) combined with a fine grain detail normal. Metallic 0.

Exposed parameters
- ``paint_color`` (float3, sRGB): the paint colour (any colour; white by default).
- ``splat_size``: size of the splats (higher: larger, fewer splats).
- ``coverage``: how much of the wall the splats cover.
- ``edges``: height of the raised rims around the splats.
- ``roughness``: the mean roughness of the paint (flat to eggshell).
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    SOFT_LIGHT,
    SUBTRACT,
    constant_map,
    gradient_over,
    keys_near,
    set_material_outputs,
)
from blender_match.library.expressions import clamp, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

SHADE_TONES = [(0.0, (0.72, 0.72, 0.72)), (0.35, (0.92, 0.92, 0.92)), (1.0, (1.0, 1.0, 1.0))]
MOTTLE_TONES = [(0.0, (0.46, 0.46, 0.46)), (1.0, (0.54, 0.54, 0.54))]
AO_TONES = [(0.0, (0.3, 0.3, 0.3)), (1.0, (1.0, 1.0, 1.0))]


def build() -> SbsGraph:
    g = SbsGraph("stucco")
    g.expose("paint_color", (0.86, 0.85, 0.82), min=0.0, max=1.0)
    g.expose("splat_size", 1.0, min=0.5, max=2.0)
    g.expose("coverage", 0.5, min=0.0, max=1.0)
    g.expose("edges", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.8, min=0.3, max=1.0)
    g.expose("relief", 0.5, min=0.0, max=1.0)
    size = get("splat_size")
    edges = get("edges")

    # ---- splats -------------------------------------------------------------------------------
    g.add("blobs_big", "perlin_noise", seed=101, scale=9.0)
    g.bind("blobs_big", "scale", clamp(9.0 / size, 2.0, 32.0).graph())
    g.add("blobs_small", "perlin_noise", seed=102, scale=20.0)
    g.bind("blobs_small", "scale", clamp(20.0 / size, 4.0, 64.0).graph())
    g.add("fray", "bnw_spots_3", seed=103, scale=10.0)
    g.add("blobs", "blend", {"source": "blobs_small", "destination": "blobs_big"}, blendingmode=ADD_SUB,
          opacitymult=0.3)
    g.add("blobs_frayed", "blend", {"source": "fray", "destination": "blobs"}, blendingmode=ADD_SUB,
          opacitymult=0.07)
    g.add("splat_mask", "histogram_scan", {"input_1": "blobs_frayed"}, position=0.55, contrast=0.85)
    g.bind("splat_mask", "position", lerp(0.1, 0.65, get("coverage")).graph())
    g.add("plateau", "blur_hq_grayscale", {"source": "splat_mask"}, intensity=2.0)
    g.add("rim", "histogram_select", {"input": "plateau"}, position=0.72, range=0.12, contrast=0.3)
    g.add("rim_soft", "blur_hq_grayscale", {"source": "rim"}, intensity=0.8)

    # ---- textures -----------------------------------------------------------------------------
    g.add("spray", "bnw_spots_3", seed=104, scale=28.0)
    g.add("peel", "perlin_noise", seed=105, scale=48.0)
    g.add("spray_peel", "blend", {"source": "peel", "destination": "spray"}, blendingmode=ADD_SUB,
          opacitymult=0.4)
    g.add("mottle", "clouds_1", seed=106, scale=2.0)

    # ---- height ------------------------------------------------------------------------------
    g.add("coat", "histogram_range", {"input": "spray_peel"}, range=0.12, position=0.2)
    g.add("top", "histogram_range", {"input": "spray_peel"}, range=0.05, position=0.72)
    g.add("h_splat", "blend", {"source": "top", "destination": "coat", "opacity": "plateau"}, blendingmode=MAX)
    g.add("h_rim", "blend", {"source": "rim_soft", "destination": "h_splat"}, blendingmode=ADD, opacitymult=0.1)
    g.bind("h_rim", "opacitymult", lerp(0.0, 0.35, edges).graph())
    g.add("h_undulate", "blend", {"source": "mottle", "destination": "h_rim"}, blendingmode=ADD_SUB,
          opacitymult=0.06)
    g.add("height", "histogram_range", {"input": "h_undulate"}, range=0.9, position=0.5)

    g.add("n_main", "normal", {"input1": "height"}, intensity=5.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(0.5, 10.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "spray"}, intensity=0.4, inversedy=True, input2alpha=False)
    g.add("normal", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.12, spreading=0.06,
          model=OUR_OCCLUSION)

    # ---- colour --------------------------------------------------------------------------------
    g.add("paint", "uniform", outputcolor=(0.86, 0.85, 0.82, 1.0))
    g.bind("paint", "outputcolor", vector(get("paint_color", 3), 1.0).graph())
    gradient_over(g, "paint_shaded", "shade", "height", SHADE_TONES, "paint", blendingmode=MULTIPLY, opacitymult=0.4)
    gradient_over(g, "paint_mottled", "mottle_tones", "mottle", MOTTLE_TONES, "paint_shaded", blendingmode=SOFT_LIGHT,
                  opacitymult=0.6)
    gradient_over(g, "basecolor", "ao_color", "ao", AO_TONES, "paint_mottled", blendingmode=MULTIPLY, opacitymult=0.35)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "spray"}, range=0.08, position=0.8)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "plateau", "destination": "rough_base"}, blendingmode=SUBTRACT,
          opacitymult=0.06)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "plaster"

SAMPLE_RANGES = {
    "exposed.paint_color": ((0.15, 0.15, 0.15), (0.95, 0.95, 0.95)),
    "exposed.splat_size": (0.6, 1.6),
    "exposed.coverage": (0.3, 0.8),
    "exposed.edges": (0.1, 0.9),
    "exposed.roughness": (0.6, 0.95),
    "exposed.relief": (0.3, 0.8),
    "fray.scale": (6.0, 16.0),
    "spray.scale": (20.0, 32.0),
    "peel.scale": (32.0, 64.0),
    "mottle.scale": (1.5, 3.0),
    "blobs_frayed.opacitymult": (0.03, 0.15),
    "plateau.intensity": (1.2, 3.0),
    "shade.colors": keys_near(SHADE_TONES, 0.03),
    "mottle_tones.colors": keys_near(MOTTLE_TONES, 0.02),
    "ao_color.colors": keys_near(AO_TONES, 0.05),
    "n_grain.intensity": (0.2, 0.8),
    "top.range": (0.02, 0.08),
    "coat.range": (0.08, 0.2),
    "rim.position": (0.65, 0.8),
}
