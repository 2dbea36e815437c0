"""Wood planks: a varnished hardwood floor of long staggered planks (oak-like by default).

Structure
- Layout: two Brick Generators with one seed, one bevelled (the plank relief, thin gaps) and one
  flat with full luminance randomness (a per-plank random value, the "plank id").
- Grain: growth rings (Directional Noise) warped by a Perlin noise for the wavy cathedral figure,
  fine fibres and pores (Anisotropic Noise), shifted per plank by a directional warp driven by the
  plank id so every plank shows a different part of the log; a contrast node sets the grain
  contrast.
- Colour: the grain picks between a dark and a light wood colour, both derived from the exposed
  wood colour; a per-plank gradient (hue/value shifts around neutral) is overlaid, a cloud noise
  adds large-scale variation, gaps and ambient occlusion darken, worn areas of the finish lighten.
- Height: plank bevels plus the grain sunk slightly into the surface; normal from the height
  (OpenGL, inverted Y) combined with a fibre detail normal.
- Roughness: a narrow range around the exposed roughness, modulated by the grain (pores rougher),
  gaps rough, worn finish rougher. Metallic: 0.

Exposed parameters
- ``wood_color`` (float3): the mid wood colour; drives the dark and light grain colours.
- ``grain_contrast``: contrast of the grain figure (contrast node).
- ``plank_variation``: how much planks differ in tone and hue (opacity of the per-plank overlay).
- ``roughness``: mean roughness of the varnish (centre of the roughness range).
- ``wear``: worn finish: lighter, rougher patches where the grunge mask is above a threshold.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    COPY,
    MAX,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    grain_tones,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("wood_planks")
    g.expose("wood_color", (0.50, 0.33, 0.19), min=0.0, max=1.0)
    g.expose("grain_contrast", 0.35, min=0.0, max=1.0)
    g.expose("plank_variation", 0.55, min=0.0, max=1.0)
    g.expose("roughness", 0.42, min=0.1, max=0.9)
    g.expose("wear", 0.25, min=0.0, max=1.0)

    # ---- layout ------------------------------------------------------------------------------
    g.add("planks", "brick_generator", seed=11, x_amount=2, y_amount=8, offset=0.37,
          interstice=(0.004, 0.025), bevel=0.05, luminance_random=0.0)
    g.add("plank_id", "brick_generator", seed=11, x_amount=2, y_amount=8, offset=0.37,
          interstice=(0.0, 0.0), bevel=0.0, luminance_random=1.0)
    g.add("plank_mask", "histogram_scan", {"input_1": "planks"}, position=0.9, contrast=0.85)
    g.add("gap_mask", "invert_grayscale", {"source": "plank_mask"})

    # ---- grain -------------------------------------------------------------------------------
    g.add("rings", "directionnal_noise", seed=3, scale=6.0, disorder=0.2)
    g.add("clouds", "clouds_2", seed=7, scale=2.0)
    g.add("rings_wavy", "directionalwarp", {"input1": "rings", "inputintensity": "clouds"},
          intensity=7.0, warpangle=0.25)
    g.add("rings_sharp", "histogram_scan", {"input_1": "rings_wavy"}, position=0.5, contrast=0.1)
    g.add("fibres", "anisotropic_noise", seed=5, x_amount=6, y_amount=256, smoothness=0.3)
    g.add("grain_mix", "blend", {"source": "fibres", "destination": "rings_sharp"},
          blendingmode=OVERLAY, opacitymult=0.6)
    g.add("grain_shift", "directionalwarp", {"input1": "grain_mix", "inputintensity": "plank_id"},
          intensity=48.0, warpangle=0.25)
    g.add("grain", "contrast_luminosity_grayscale", {"input": "grain_shift"}, contrast=0.35, luminosity=0.0)
    g.bind("grain", "contrast", lerp(-0.4, 0.8, get("grain_contrast")).graph())

    # ---- colour ------------------------------------------------------------------------------
    wood = get("wood_color", 3)
    grain_tones(g, "wood", wood, "grain", 0.6, 1.25, (0.22, 0.14, 0.08), (0.62, 0.43, 0.26))
    gradient_over(g, "wood_planked", "plank_tone", "plank_id", [
        (0.0, (0.26, 0.25, 0.27)), (0.3, (0.46, 0.44, 0.42)), (0.65, (0.56, 0.51, 0.45)),
        (1.0, (0.74, 0.64, 0.50))], "wood_base", blendingmode=OVERLAY, opacitymult=0.55)
    g.bind("wood_planked", "opacitymult", get("plank_variation").graph())
    gradient_over(g, "wood_clouded", "cloud_tone", "clouds", [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.58, 0.56, 0.53))],
                  "wood_planked", blendingmode=SOFT_LIGHT, opacitymult=0.6)

    # wear of the finish
    g.add("grunge", "grunge_map_002", seed=8, scale=2.0, balance=0.5, contrast=0.5)
    g.add("wear_mask", "histogram_scan", {"input_1": "grunge"}, position=0.25, contrast=0.5)
    g.bind("wear_mask", "position", lerp(0.0, 0.5, get("wear")).graph())
    color_over(g, "wood_worn", "worn_color", (0.70, 0.60, 0.48, 1.0), "wood_clouded", mask="wear_mask",
               blendingmode=SOFT_LIGHT, opacitymult=0.5)

    # gaps and occlusion
    color_over(g, "wood_gaps", "gap_color", (0.05, 0.035, 0.025, 1.0), "wood_worn", mask="gap_mask", blendingmode=COPY,
               opacitymult=0.9)

    # ---- height and normal ----------------------------------------------------------------------
    g.add("pores", "histogram_scan", {"input_1": "grain"}, position=0.7, contrast=0.3, invert_position=True)
    g.add("height_grain", "blend", {"source": "pores", "destination": "planks"},
          blendingmode=SUBTRACT, opacitymult=0.05)
    g.add("height", "histogram_range", {"input": "height_grain"}, range=0.9, position=0.55)
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.12, spreading=0.1,
          model=OUR_OCCLUSION)
    ao_darken(g, "basecolor", "wood_gaps", floor=0.2, opacitymult=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=6.0, inversedy=True)
    g.add("normal_fibres", "normal", {"input1": "grain_shift"}, intensity=0.6, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_fibres"})

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_grain", "histogram_range", {"input": "pores"}, range=0.12, position=0.42)
    g.bind("rough_grain", "position", get("roughness").graph())
    g.add("rough_worn", "blend", {"source": "wear_mask", "destination": "rough_grain"},
          blendingmode=ADD, opacitymult=0.12)
    g.add("rough_gaps", "blend", {"source": "gap_mask", "destination": "rough_worn"},
          blendingmode=MAX, opacitymult=0.85)
    g.add("roughness", "passthrough", {"input": "rough_gaps"})
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "wood"

SAMPLE_RANGES = {
    "exposed.wood_color": ((0.42, 0.24, 0.12), (0.68, 0.40, 0.24)),
    "exposed.grain_contrast": (0.1, 0.7),
    "exposed.plank_variation": (0.2, 0.9),
    "exposed.roughness": (0.25, 0.7),
    "exposed.wear": (0.0, 0.7),
    "rings.scale": (4.0, 8.0),
    "rings_wavy.intensity": (3.0, 14.0),
    "grain_mix.opacitymult": (0.2, 0.7),
    "normal_main.intensity": (3.0, 10.0),
    "height_grain.opacitymult": (0.02, 0.12),
    "clouds.scale": (1.0, 4.0),
    "wood_clouded.opacitymult": (0.3, 0.9),
}
