"""Painted steel: a coat of enamel paint, from an intact coated sheet to one chipped and scratched
down to the bare metal.

Structure: the wear mask is the union of chips (a grunge map and a fractal sum, squeezed below 0.9
and histogram-scanned by the square of the wear: none at wear 0 and almost none below 0.4, so that
the sampled variants include the intact coats most painted sheets show) and scratches (sparse
white-noise dots smeared in two directions by directional blurs); the paint mask is its inverse,
slightly blurred so chip edges have a rim. The paint gets a low-frequency tone variation (clouds)
and a fine orange-peel relief (Perlin noise); the bare metal gets a brushed streak pattern. Base
colour, roughness and metallic switch between paint and metal by the paint mask; height = paint
thickness + orange peel + metal streaks; normal from height. Dust lies on top
(``authoring.dust_specks``): light grey, rough specks a hair above the coat, which a dark glossy
sheet shows as bright dots around the flash.

Exposed parameters: ``paint_color`` (sRGB), ``paint_roughness``, ``metal_color`` (sRGB tint of the
bare steel), ``metal_roughness``, ``wear`` (how much paint is gone), ``scratches`` (scratch
amount), ``dust`` (how many dust specks), ``normal_intensity``.
"""
from blender_match.library.authoring import (
    ADD,
    DUST_COLOR,
    DUST_OPACITY,
    DUST_RELIEF,
    DUST_ROUGHNESS,
    color_over,
    dust_specks,
    set_material_outputs,
)
from blender_match.library.expressions import get, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("painted_metal")
    g.expose("paint_color", [0.11, 0.27, 0.45], min=0.0, max=1.0)
    g.expose("paint_roughness", 0.42, min=0.1, max=0.9)
    g.expose("metal_color", [0.62, 0.62, 0.64], min=0.0, max=1.0)
    g.expose("metal_roughness", 0.32, min=0.05, max=0.8)
    g.expose("wear", 0.55, min=0.0, max=1.0)
    g.expose("scratches", 0.5, min=0.0, max=1.0)
    g.expose("dust", 0.2, min=0.0, max=1.0)
    g.expose("normal_intensity", 1.5, min=0.0, max=5.0)

    # chips
    g.add("chip_grunge", "bnw_spots_2", seed=17, scale=3.0, disorder=0.2)
    g.add("chip_fractal", "fractal_sum_2", seed=4, scale=3.0, roughness=0.55)
    g.add("chip_noise", "blend", {"source": "chip_fractal", "destination": "chip_grunge"},
          blendingmode=9, opacitymult=0.6)
    # the noise squeezed below 0.9, so that a small wear scans past all of it (its brightest
    # patches would otherwise chip the coat at any wear above 0)
    g.add("chip_level", "histogram_range", {"input": "chip_noise"}, range=0.9, position=0.45)
    g.add("chips", "histogram_scan", {"input_1": "chip_level"}, contrast=0.82)
    g.bind("chips", "position", (0.6 * get("wear") * get("wear")).graph())

    # scratches
    g.add("scratch_dots", "white_noise", seed=29)
    g.add("scratch_sparse", "histogram_scan", {"input_1": "scratch_dots"}, position=0.003, contrast=0.6)
    g.add("scratch_a", "dirmotionblur", {"input1": "scratch_sparse"}, intensity=24.0, mblurangle=0.08)
    g.add("scratch_shift", "transformation", {"input1": "scratch_sparse"}, offset=[0.21, 0.53])
    g.add("scratch_b", "dirmotionblur", {"input1": "scratch_shift"}, intensity=16.0, mblurangle=0.71)
    g.add("scratch_max", "blend", {"source": "scratch_b", "destination": "scratch_a"}, blendingmode=5)
    g.add("scratch_mask", "histogram_scan", {"input_1": "scratch_max"}, contrast=0.7)
    g.bind("scratch_mask", "position", (0.12 * get("scratches")).graph())

    # paint mask
    g.add("wear_mask", "blend", {"source": "scratch_mask", "destination": "chips"}, blendingmode=5)
    g.add("paint_mask_sharp", "invert_grayscale", {"source": "wear_mask"})
    g.add("paint_mask", "blur", {"input1": "paint_mask_sharp"}, intensity=0.6)

    # paint colour and relief
    g.add("paint_base", "uniform")
    g.bind("paint_base", "outputcolor", vector(get("paint_color", 3), 1.0).graph())
    g.add("paint_clouds", "clouds_2", seed=8, scale=2.0, disorder=0.1)
    color_over(g, "paint_color", "paint_tone", [0.82, 0.83, 0.86, 1.0], "paint_base", mask="paint_clouds",
               blendingmode=3, opacitymult=0.35)
    g.add("orange_peel", "perlin_noise", seed=2, scale=24.0, disorder=0.0)

    # bare metal
    g.add("metal_streaks", "anisotropic_noise", seed=13, x_amount=4, y_amount=160, smoothness=0.4)
    g.add("metal_base", "uniform")
    g.bind("metal_base", "outputcolor", vector(get("metal_color", 3), 1.0).graph())
    g.add("metal_streak_color", "gradient", {"input1": "metal_streaks"}, positions=[0.0, 1.0],
          colors=[0.86, 0.86, 0.87, 1.0, 1.0, 1.0, 1.0, 1.0])
    g.add("metal_color", "blend", {"source": "metal_streak_color", "destination": "metal_base"}, blendingmode=3)

    g.add("coat_color", "blend", {"source": "paint_color", "destination": "metal_color", "opacity": "paint_mask"})
    dust = dust_specks(g, get("dust"), seeds=(31, 37))
    color_over(g, "basecolor", "dust_color", DUST_COLOR, "coat_color", mask=dust, opacitymult=DUST_OPACITY)

    # roughness
    g.add("metal_rough", "histogram_range", {"input": "metal_streaks"}, range=0.12)
    g.bind("metal_rough", "position", get("metal_roughness").graph())
    g.add("paint_rough", "histogram_range", {"input": "paint_clouds"}, range=0.1)
    g.bind("paint_rough", "position", get("paint_roughness").graph())
    g.add("coat_rough", "blend", {"source": "paint_rough", "destination": "metal_rough", "opacity": "paint_mask"})
    g.add("dust_rough", "uniform", colorswitch=False, outputcolor=DUST_ROUGHNESS)
    g.add("roughness", "blend", {"source": "dust_rough", "destination": "coat_rough", "opacity": dust})

    # metallic
    g.add("metal_one", "uniform", colorswitch=False, outputcolor=[1.0, 1.0, 1.0, 1.0])
    g.add("paint_zero", "uniform", colorswitch=False, outputcolor=[0.0, 0.0, 0.0, 1.0])
    g.add("metallic", "blend", {"source": "paint_zero", "destination": "metal_one", "opacity": "paint_mask"})

    # height
    g.add("paint_height", "histogram_range", {"input": "paint_mask"}, range=0.3, position=0.55)
    g.add("peel_height", "blend", {"source": "orange_peel", "destination": "paint_height",
                                   "opacity": "paint_mask"}, blendingmode=4, opacitymult=0.06)
    g.add("coat_height", "blend", {"source": "metal_streaks", "destination": "peel_height",
                                   "opacity": "wear_mask"}, blendingmode=4, opacitymult=0.04)
    g.add("height", "blend", {"source": dust, "destination": "coat_height"}, blendingmode=ADD, opacitymult=DUST_RELIEF)
    g.add("normal", "normal", {"input1": "height"})
    g.bind("normal", "intensity", get("normal_intensity").graph())

    set_material_outputs(g)
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.paint_color": ([0.02, 0.02, 0.02], [0.9, 0.9, 0.9]),
    "exposed.paint_roughness": (0.12, 0.7),
    "exposed.metal_color": ([0.5, 0.5, 0.5], [0.75, 0.75, 0.77]),
    "exposed.metal_roughness": (0.15, 0.55),
    "exposed.wear": (0.0, 0.9),
    "exposed.dust": (0.0, 0.8),
    "exposed.scratches": (0.0, 1.0),
    "exposed.normal_intensity": (0.5, 3.0),
    "chip_grunge.scale": (2.0, 5.0),
    "chip_noise.opacitymult": (0.2, 0.9),
    "chips.contrast": (0.6, 0.95),
    "peel_height.opacitymult": (0.0, 0.15),
    "scratch_a.mblurangle": (0.0, 0.25),
    "metal_one.outputcolor": (1.0, 1.0),
    "paint_zero.outputcolor": (0.0, 0.0),
    "metallic.opacitymult": (1.0, 1.0),  # paint is a dielectric: no sample tints it metallic
}
