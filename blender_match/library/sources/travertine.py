"""Travertine: honed beige travertine limestone with elongated pits and voids and banded veining along one direction.

Structure
- Banding: travertine is laid down in thin layers, so a noise stretched along one axis
  (Directional Noise over a broad cloud), wobbled by a soft warp, gives the band field. A gradient
  turns it into cream and tan bands, and a narrow histogram select of the same field draws thin
  darker veins along the layer boundaries.
- Voids: the gas holes of travertine are flattened along the layers. Sparse spots (thresholded
  Gaussian spots) are smeared along the band direction by two directional blurs (a box
  blur twice: a tapered profile, so the threshold gives pointed lens shapes) and thresholded
  again, giving lens-shaped pits of a few mm to 2 cm; they are favoured in some layers (multiplied
  by a band mask) as in real slabs. A few fine pinholes (thresholded white noise) are added.
- Height: a flat honed plane; voids sunk deep with soft walls; a very faint band relief.
- Colour: the exposed stone colour shaded by the bands, veins darker and browner, voids dark
  brown-grey (shadow and dirt), faint cloudy mottling.
- Roughness: the exposed honed level; voids and veins rougher. Metallic 0. AO from the height
  darkens inside the voids.

Exposed parameters
- ``stone_color`` (float3): the travertine colour (ivory, beige, walnut, silver-grey, red).
- ``voids``: how many pits and voids.
- ``banding``: contrast of the layer bands and veins.
- ``void_length``: how elongated the voids are along the layers.
- ``roughness``: the finish (honed ~0.5, polished lower, tumbled higher).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    SUBTRACT,
    color_over,
    constant_map,
    gradient_over,
    pinned_keys,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

BANDS = [(0.0, (0.4, 0.4, 0.4)), (0.3, (0.47, 0.47, 0.47)), (0.5, (0.53, 0.53, 0.53)), (0.7, (0.49, 0.49, 0.49)),
         (1.0, (0.6, 0.6, 0.6))]
VEIN_COLOR = (0.55, 0.45, 0.34, 1.0)
VOID_COLOR = (0.42, 0.37, 0.3, 1.0)
AO_TONE = [(0.0, (0.35, 0.35, 0.35)), (1.0, (1.0, 1.0, 1.0))]
MOTTLE = [(0.0, (0.45, 0.45, 0.45)), (1.0, (0.55, 0.55, 0.55))]


def build() -> SbsGraph:
    g = SbsGraph("travertine")
    g.expose("stone_color", (0.80, 0.72, 0.60), min=0.0, max=1.0)
    g.expose("voids", 0.5, min=0.0, max=1.0)
    g.expose("banding", 0.5, min=0.0, max=1.0)
    g.expose("void_length", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.5, min=0.1, max=0.95)

    # ---- band field ---------------------------------------------------------------------------
    g.add("band_broad", "clouds_1", seed=81, scale=2.0)
    g.add("band_dir", "directionnal_noise", seed=82, scale=2.0)
    g.add("band_mix", "blend", {"source": "band_dir", "destination": "band_broad"}, blendingmode=ADD_SUB,
          opacitymult=0.7)
    g.add("band_wobble", "clouds_2", seed=83, scale=2.0)
    g.add("band_warp", "warp", {"input1": "band_mix", "inputgradient": "band_wobble"}, intensity=0.05)
    g.add("band_smooth", "blur_hq_grayscale", {"source": "band_warp"}, intensity=1.5)
    g.add("band_field", "auto_levels", {"input": "band_smooth"})
    g.add("veins", "histogram_select", {"input": "band_field"}, position=0.45, range=0.008, contrast=0.6)
    g.add("veins_soft", "blur", {"input1": "veins"}, intensity=0.4)

    # ---- voids --------------------------------------------------------------------------------
    g.add("void_spots", "gaussian_spots_1", seed=84, scale=5.0)
    g.add("void_seeds", "histogram_scan", {"input_1": "void_spots"}, position=0.15, contrast=0.7)
    g.bind("void_seeds", "position", lerp(0.01, 0.2, get("voids")).graph())
    g.add("void_layers", "histogram_scan", {"input_1": "band_field"}, position=0.6, contrast=0.3)
    g.add("void_layered", "blend", {"source": "void_layers", "destination": "void_seeds"}, blendingmode=MULTIPLY,
          opacitymult=0.7)
    g.add("void_streak", "dirmotionblur", {"input1": "void_layered"}, intensity=6.0, mblurangle=0.0)
    g.bind("void_streak", "intensity", lerp(3.0, 12.0, get("void_length")).graph())
    g.add("void_taper", "dirmotionblur", {"input1": "void_streak"}, intensity=6.0, mblurangle=0.0)
    g.bind("void_taper", "intensity", lerp(3.0, 12.0, get("void_length")).graph())
    g.add("void_smear", "blur_hq_grayscale", {"source": "void_taper"}, intensity=1.0)
    g.add("void_mask", "histogram_scan", {"input_1": "void_smear"}, position=0.65, contrast=0.75)
    g.add("pin_noise", "white_noise", seed=85)
    g.add("pins", "histogram_scan", {"input_1": "pin_noise"}, position=0.004, contrast=0.8)
    g.add("pins_smear", "dirmotionblur", {"input1": "pins"}, intensity=1.0, mblurangle=0.0)
    g.add("pins_mask", "histogram_scan", {"input_1": "pins_smear"}, position=0.7, contrast=0.5)
    g.add("holes", "blend", {"source": "pins_mask", "destination": "void_mask"}, blendingmode=MAX, opacitymult=0.8)
    g.add("holes_soft", "blur_hq_grayscale", {"source": "holes"}, intensity=0.6)

    # ---- height -------------------------------------------------------------------------------
    g.add("h_band", "histogram_range", {"input": "band_field"}, range=0.04, position=0.8)
    g.add("h_holes", "blend", {"source": "holes_soft", "destination": "h_band"}, blendingmode=SUBTRACT,
          opacitymult=0.6)
    g.add("void_floor", "fractal_sum_1", seed=86, scale=8.0)
    g.add("height", "blend", {"source": "void_floor", "destination": "h_holes", "opacity": "holes_soft"},
          blendingmode=ADD_SUB, opacitymult=0.15)
    g.add("normal", "normal", {"input1": "height"}, intensity=6.0, inversedy=True, input2alpha=False)
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.2, spreading=0.1,
          model=OUR_OCCLUSION)

    # ---- colour -------------------------------------------------------------------------------
    g.add("stone", "uniform", outputcolor=(0.80, 0.72, 0.60, 1.0))
    g.bind("stone", "outputcolor", vector(get("stone_color", 3), 1.0).graph())
    gradient_over(g, "col_bands", "band_tone", "band_field", BANDS, "stone", blendingmode=ADD_SUB, opacitymult=0.5)
    g.bind("col_bands", "opacitymult", lerp(0.0, 1.0, get("banding")).graph())
    g.add("mottle_noise", "clouds_2", seed=87, scale=3.0)
    gradient_over(g, "col_mottle", "mottle", "mottle_noise", MOTTLE, "col_bands", blendingmode=ADD_SUB, opacitymult=0.4)
    color_over(g, "col_veins", "vein_color", VEIN_COLOR, "col_mottle", mask="veins_soft", blendingmode=MULTIPLY,
               opacitymult=0.5)
    g.bind("col_veins", "opacitymult", lerp(0.0, 0.9, get("banding")).graph())
    color_over(g, "col_voids", "void_color", VOID_COLOR, "col_veins", mask="holes_soft", blendingmode=MULTIPLY,
               opacitymult=0.8)
    gradient_over(g, "basecolor", "ao_tone", "ao", AO_TONE, "col_voids", blendingmode=MULTIPLY, opacitymult=0.5)

    # ---- roughness ----------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "mottle_noise"}, range=0.06, position=0.5)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_veins", "blend", {"source": "veins_soft", "destination": "r_base"}, blendingmode=ADD, opacitymult=0.08)
    g.add("roughness", "blend", {"source": "holes_soft", "destination": "r_veins"}, blendingmode=ADD,
          opacitymult=0.35)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "stone"


SAMPLE_RANGES = {
    "exposed.stone_color": ((0.74, 0.62, 0.48), (0.93, 0.82, 0.72)),
    "exposed.voids": (0.15, 0.9),
    "exposed.banding": (0.15, 0.9),
    "exposed.void_length": (0.2, 1.0),
    "exposed.roughness": (0.3, 0.75),
    "band_mix.opacitymult": (0.4, 0.9),
    "band_warp.intensity": (0.0, 0.1),
    "veins.position": (0.3, 0.7),
    "veins.range": (0.004, 0.015),
    "band_smooth.intensity": (0.5, 3.0),
    "void_mask.position": (0.55, 0.75),
    "void_layered.opacitymult": (0.3, 0.9),
    "pins.position": (0.0, 0.01),
    "normal.intensity": (3.0, 10.0),
    "void_streak.mblurangle": (0.0, 0.0),
    "void_taper.mblurangle": (0.0, 0.0),
    "pins_smear.mblurangle": (0.0, 0.0),
    "pins_smear.intensity": (0.5, 1.5),
    "void_spots.scale": (4.0, 6.5),
    "void_smear.intensity": (0.5, 1.5),
    "holes_soft.intensity": (0.3, 1.0),
    "veins_soft.intensity": (0.2, 0.8),
    "vein_color.outputcolor": ((0.45, 0.36, 0.26, 1.0), (0.65, 0.56, 0.46, 1.0)),
    "void_color.outputcolor": ((0.28, 0.24, 0.2, 1.0), (0.55, 0.5, 0.42, 1.0)),
    **{f"{node}.{p}": r for node, stops in (("band_tone", BANDS), ("mottle", MOTTLE), ("ao_tone", AO_TONE))
       for p, r in pinned_keys(stops).items()},
}
