"""Brushed stainless steel: fine parallel brushing lines, light scratches and fingerprint smudges.

Structure: the brushing is three layers of horizontal streaks (fine and coarse anisotropic noise,
white noise smeared by a directional blur) mixed and levelled into one streak map; two scratch
generators (along the grain and random) give a scratch mask; a grunge map gives smudges; a cloud
noise adds large, soft variation. Height = streaks minus scratch grooves; normal from height. Base
colour = the metal tint times a gradient map of the streaks, with brighter scratches and darker
smudges. Roughness = the streaks remapped around the roughness slider, smoother in scratches and
rougher under smudges. Metallic = 1. The brushing also makes the highlight anisotropic: the
anisotropy level is the ``anisotropy`` slider and the angle 0, the streaks running along +u (so the
highlight stretches along v, across them).

Exposed parameters: ``metal_color`` (sRGB tint), ``roughness``, ``brush_strength`` (contrast of the
brushing in colour, roughness and relief), ``scratches`` (scratch visibility), ``smudges``
(fingerprint amount), ``normal_intensity``, ``anisotropy`` (how far the highlight stretches).
"""
from blender_match.library.authoring import brushing, color_over, constant_map, set_material_outputs
from blender_match.library.expressions import get, gray4, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("brushed_metal")
    g.expose("metal_color", [0.72, 0.73, 0.75], min=0.0, max=1.0)
    g.expose("roughness", 0.3, min=0.05, max=0.8)
    g.expose("brush_strength", 0.6, min=0.0, max=1.0)
    g.expose("scratches", 0.35, min=0.0, max=1.0)
    g.expose("smudges", 0.3, min=0.0, max=1.0)
    g.expose("normal_intensity", 1.2, min=0.0, max=4.0)
    g.expose("anisotropy", 0.6, min=0.0, max=1.0)

    # brushing streaks
    g.add("streak_fine", "anisotropic_noise", seed=11, x_amount=3, y_amount=256, smoothness=0.25)
    g.add("streak_coarse", "anisotropic_noise", seed=23, x_amount=2, y_amount=48, smoothness=0.7)
    g.add("grain", "white_noise", seed=5)
    g.add("grain_smear", "dirmotionblur", {"input1": "grain"}, intensity=20.0, mblurangle=0.0)
    g.add("grain_level", "histogram_range", {"input": "grain_smear"}, range=1.0, position=0.5)
    g.add("grain_contrast", "contrast_luminosity_grayscale", {"input": "grain_level"}, contrast=0.8)
    g.add("streak_mix", "blend", {"source": "streak_coarse", "destination": "streak_fine"},
          blendingmode=9, opacitymult=0.45)
    g.add("streak_all", "blend", {"source": "grain_contrast", "destination": "streak_mix"},
          blendingmode=0, opacitymult=0.4)
    g.add("streaks", "histogram_scan", {"input_1": "streak_all"}, position=0.5)
    g.bind("streaks", "contrast", (0.7 * get("brush_strength")).graph())

    # large soft variation
    g.add("clouds", "clouds_2", seed=7, scale=1.0, disorder=0.2)

    # scratches: sparse dots smeared along the grain, and across it
    g.add("scratch_dots", "white_noise", seed=31)
    g.add("scratch_sparse", "histogram_scan", {"input_1": "scratch_dots"}, position=0.004, contrast=0.6)
    g.add("scratch_grain", "dirmotionblur", {"input1": "scratch_sparse"}, intensity=28.0, mblurangle=0.004)
    g.add("scratch_shift", "transformation", {"input1": "scratch_sparse"}, offset=[0.37, 0.61])
    g.add("scratch_cross", "dirmotionblur", {"input1": "scratch_shift"}, intensity=18.0, mblurangle=0.13)
    g.add("scratch_max", "blend", {"source": "scratch_cross", "destination": "scratch_grain"}, blendingmode=5)
    g.add("scratch_mask", "levels", {"input1": "scratch_max"}, levelinhigh=[0.06, 0.06, 0.06, 1.0])
    g.bind("scratch_mask", "levelouthigh", gray4(get("scratches")).graph())

    # fingerprint smudges
    g.add("smudge_noise", "grunge_map_002", seed=3, scale=2.0, disorder=0.3, balance=0.45, contrast=0.6)
    g.add("smudge_mask", "histogram_scan", {"input_1": "smudge_noise"}, position=0.35, contrast=0.3)

    # height and normal
    g.add("height_streaks", "histogram_range", {"input": "streaks"}, position=0.5)
    g.bind("height_streaks", "range", (0.25 * get("brush_strength")).graph())
    g.add("height", "blend", {"source": "scratch_mask", "destination": "height_streaks"},
          blendingmode=2, opacitymult=0.35)
    g.add("normal", "normal", {"input1": "height"})
    g.bind("normal", "intensity", get("normal_intensity").graph())

    # base colour
    g.add("tint", "uniform")
    g.bind("tint", "outputcolor", vector(get("metal_color", 3), 1.0).graph())
    g.add("streak_color", "gradient", {"input1": "streaks"}, positions=[0.0, 0.55, 1.0],
          colors=[0.86, 0.86, 0.87, 1.0, 0.96, 0.96, 0.96, 1.0, 1.0, 1.0, 1.0, 1.0])
    g.add("color_streaked", "blend", {"source": "streak_color", "destination": "tint"}, blendingmode=3)
    color_over(g, "color_clouds", "cloud_tone", [0.88, 0.88, 0.9, 1.0], "color_streaked", mask="clouds", blendingmode=3,
               opacitymult=0.5)
    color_over(g, "color_scratched", "scratch_bright", [0.95, 0.95, 0.96, 1.0], "color_clouds", mask="scratch_mask",
               blendingmode=5, opacitymult=0.6)
    color_over(g, "basecolor", "smudge_color", [0.55, 0.54, 0.52, 1.0], "color_scratched", mask="smudge_mask",
               blendingmode=3)
    g.bind("basecolor", "opacitymult", (0.6 * get("smudges")).graph())

    # roughness
    g.add("rough_streaks", "histogram_range", {"input": "streaks"})
    g.bind("rough_streaks", "position", get("roughness").graph())
    g.bind("rough_streaks", "range", (0.08 + 0.16 * get("brush_strength")).graph())
    g.add("rough_clouds", "blend", {"source": "clouds", "destination": "rough_streaks"},
          blendingmode=4, opacitymult=0.08)
    g.add("rough_smudge_value", "uniform", colorswitch=False, outputcolor=[0.62, 0.62, 0.62, 1.0])
    g.add("rough_smudged", "blend", {"source": "rough_smudge_value", "destination": "rough_clouds",
                                     "opacity": "smudge_mask"})
    g.bind("rough_smudged", "opacitymult", get("smudges").graph())
    g.add("roughness", "blend", {"source": "scratch_mask", "destination": "rough_smudged"},
          blendingmode=2, opacitymult=0.25)

    constant_map(g, "metallic", 1.0)
    brushing(g, get("anisotropy"), 0.0)  # the streaks (anisotropic noise, motion blur at angle 0) run along +u

    set_material_outputs(g, anisotropy=True)
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.metal_color": ([0.55, 0.55, 0.56], [0.85, 0.86, 0.88]),
    "exposed.roughness": (0.12, 0.55),
    "exposed.brush_strength": (0.2, 1.0),
    "exposed.scratches": (0.0, 0.8),
    "exposed.smudges": (0.0, 0.7),
    "exposed.normal_intensity": (0.4, 2.5),
    "exposed.anisotropy": (0.2, 0.9),
    "grain_smear.intensity": (8.0, 32.0),
    "streak_mix.opacitymult": (0.1, 0.8),
    "clouds.scale": (1.0, 3.0),
    "scratch_grain.intensity": (12.0, 32.0),
    "scratch_cross.mblurangle": (0.05, 0.45),
}
