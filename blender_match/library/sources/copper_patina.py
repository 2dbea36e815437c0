"""Material: oxidised copper, warm metal with green-blue verdigris patches and runs over brown tarnish.

Structure
- Patina mask: large clouds mixed with a grunge map (where moisture sat) plus vertical runs
  (the mask smeared downwards by a directional blur, as verdigris washes down a sheet), broken
  up at its edges by a fine fractal noise, then histogram-scanned by the exposed patina amount.
  A softened copy gives the crust a rim of half-covered copper.
- Copper: the exposed copper colour, mottled by clouds and darkened to brown tarnish where a
  second cloud/dirt mask says so (exposed tarnish), with faint polishing streaks.
- Verdigris: a fractal/crystal texture mapped through a gradient (dark teal, blue-green, pale
  powdery green) and tinted by the exposed patina colour; it is a dielectric crust, so metallic
  is 0 and roughness high there.
- Height: a slightly raised, grainy crust over a smooth, faintly pitted copper; normal from it,
  ambient occlusion from the height.
- Metallic: 1 on copper, 0 under the patina (the soft mask, so half-covered rims are mixed).

Exposed parameters
- ``patina_amount``: how much of the surface the verdigris covers (drives colour, height, metallic).
- ``patina_color`` (float3): the verdigris tint (blue-green to pale green).
- ``copper_color`` (float3): the clean metal's colour (from bright pink copper to bronze).
- ``tarnish``: how much of the bare copper is darkened to brown.
- ``metal_roughness``: roughness of the bare copper.
- ``normal_intensity``: strength of the crust relief.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MULTIPLY,
    OVERLAY,
    SUBTRACT,
    ao_darken,
    color_over,
    gradient_keys,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("copper_patina")
    g.expose("patina_amount", 0.5, min=0.0, max=1.0)
    g.expose("patina_color", (0.42, 0.70, 0.60), min=0.0, max=1.0)
    g.expose("copper_color", (0.72, 0.42, 0.28), min=0.0, max=1.0)
    g.expose("tarnish", 0.45, min=0.0, max=1.0)
    g.expose("metal_roughness", 0.35, min=0.1, max=0.8)
    g.expose("normal_intensity", 2.0, min=0.0, max=6.0)

    # ---- patina mask --------------------------------------------------------------------------
    g.add("patch_clouds", "clouds_2", seed=12, scale=1.0, disorder=0.2)
    g.add("patch_grunge", "grunge_map_012", seed=5, scale=2.0)
    g.add("patch_mix", "blend", {"source": "patch_grunge", "destination": "patch_clouds"},
          blendingmode=OVERLAY, opacitymult=0.6)
    g.add("runs", "dirmotionblur", {"input1": "patch_mix"}, intensity=24.0, mblurangle=0.25)
    g.add("run_streaks", "anisotropic_noise", seed=23, x_amount=80, y_amount=3, smoothness=0.6)
    g.add("run_lines", "histogram_scan", {"input_1": "run_streaks"}, position=0.45, contrast=0.5)
    g.add("runs_streaky", "blend", {"source": "run_lines", "destination": "runs"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("runs_mix", "blend", {"source": "runs_streaky", "destination": "patch_mix"},
          blendingmode=ADD, opacitymult=0.45)
    g.add("edge_noise", "fractal_sum_1", seed=27, scale=6.0)
    g.add("patch_edges", "blend", {"source": "edge_noise", "destination": "runs_mix"},
          blendingmode=ADD_SUB, opacitymult=0.35)
    g.add("patina_mask", "histogram_scan", {"input_1": "patch_edges"}, contrast=0.7)
    g.bind("patina_mask", "position", lerp(0.05, 0.9, get("patina_amount")).graph())
    g.add("patina_soft", "blur", {"input1": "patina_mask"}, intensity=1.5)

    # ---- copper ------------------------------------------------------------------------------
    g.add("copper_base", "uniform", outputcolor=(0.72, 0.42, 0.28, 1.0))
    g.bind("copper_base", "outputcolor", vector(get("copper_color", 3), 1.0).graph())
    g.add("copper_clouds", "clouds_1", seed=9, scale=3.0)
    gradient_over(g, "copper_mottled", "copper_mottle", "copper_clouds",
                  [(0.0, (0.42, 0.40, 0.40)), (1.0, (0.62, 0.60, 0.58))], "copper_base", blendingmode=OVERLAY,
                  opacitymult=0.7)
    g.add("polish", "anisotropic_noise", seed=19, x_amount=4, y_amount=192, smoothness=0.5)
    ao_darken(g, "copper_polished", "copper_mottled", floor=0.93, opacitymult=0.5, ao="polish",
              color_name="polish_tone")
    g.add("tarnish_noise", "clouds_2", seed=31, scale=2.0)
    g.add("tarnish_mix", "blend", {"source": "copper_clouds", "destination": "tarnish_noise"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("tarnish_mask", "histogram_scan", {"input_1": "tarnish_mix"}, contrast=0.35)
    g.bind("tarnish_mask", "position", lerp(0.0, 0.85, get("tarnish")).graph())
    color_over(g, "copper_tarnished", "tarnish_color", (0.42, 0.28, 0.20, 1.0), "copper_polished", mask="tarnish_mask",
               blendingmode=MULTIPLY, opacitymult=0.85)

    # ---- verdigris ---------------------------------------------------------------------------
    g.add("crust_fractal", "fractal_sum_4", seed=8, scale=1.0)
    g.add("crust_grain", "bnw_spots_3", seed=16, scale=4.0)
    g.add("crust_detail", "blend", {"source": "crust_grain", "destination": "crust_fractal"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("verdigris_grad", "gradient", {"input1": "crust_detail"}, **gradient_keys([
        (0.0, (0.45, 0.55, 0.52)), (0.4, (0.80, 0.90, 0.86)), (0.75, (0.95, 1.0, 0.95)),
        (1.0, (1.0, 1.0, 1.0))]))
    g.add("patina_tint", "uniform", outputcolor=(0.42, 0.70, 0.60, 1.0))
    g.bind("patina_tint", "outputcolor", vector(get("patina_color", 3), 1.0).graph())
    g.add("verdigris_flat", "blend", {"source": "verdigris_grad", "destination": "patina_tint"},
          blendingmode=MULTIPLY)
    gradient_over(g, "verdigris", "verdigris_shade", "patch_grunge",
                  [(0.0, (0.62, 0.70, 0.60)), (0.5, (0.95, 0.97, 0.95)), (1.0, (1.0, 1.0, 1.0))], "verdigris_flat",
                  blendingmode=MULTIPLY, opacitymult=0.8)
    g.add("rim_dark", "uniform", outputcolor=(0.55, 0.45, 0.40, 1.0))
    g.add("rim_mask", "histogram_select", {"input": "patina_soft"}, position=0.4, range=0.3, contrast=0.3)
    g.add("copper_rim", "blend", {"source": "rim_dark", "destination": "copper_tarnished",
                                  "opacity": "rim_mask"}, blendingmode=MULTIPLY, opacitymult=0.7)

    g.add("basecolor", "blend", {"source": "verdigris", "destination": "copper_rim", "opacity": "patina_soft"})

    # ---- height and normal -------------------------------------------------------------------
    g.add("pits_noise", "bnw_spots_3", seed=44, scale=6.0)
    g.add("pits", "histogram_scan", {"input_1": "pits_noise"}, position=0.15, contrast=0.6,
          invert_position=True)
    g.add("copper_height", "blend", {"source": "pits", "destination": "copper_clouds"},
          blendingmode=SUBTRACT, opacitymult=0.3)
    g.add("copper_flat", "histogram_range", {"input": "copper_height"}, range=0.1, position=0.35)
    g.add("crust_height", "histogram_range", {"input": "crust_detail"}, range=0.35, position=0.65)
    g.add("height", "blend", {"source": "crust_height", "destination": "copper_flat", "opacity": "patina_soft"})
    normal_and_ao(g, "height", intensity=2.0, height_depth=0.12, spreading=0.08)
    g.bind("normal", "intensity", get("normal_intensity").graph())

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("copper_rough", "histogram_range", {"input": "copper_clouds"}, range=0.12)
    g.bind("copper_rough", "position", get("metal_roughness").graph())
    g.add("copper_rough_tarnish", "blend", {"source": "tarnish_mask", "destination": "copper_rough"},
          blendingmode=ADD_SUB, opacitymult=0.15)
    g.add("crust_rough", "histogram_range", {"input": "crust_detail"}, range=0.12, position=0.86)
    g.add("roughness", "blend", {"source": "crust_rough", "destination": "copper_rough_tarnish",
                                 "opacity": "patina_soft"})
    g.add("metal_one", "uniform", colorswitch=False, outputcolor=(1.0, 1.0, 1.0, 1.0))
    g.add("crust_zero", "uniform", colorswitch=False, outputcolor=(0.0, 0.0, 0.0, 1.0))
    g.add("metallic", "blend", {"source": "crust_zero", "destination": "metal_one", "opacity": "patina_soft"})

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.patina_amount": (0.15, 0.85),
    "exposed.patina_color": ((0.25, 0.58, 0.45), (0.45, 0.82, 0.72)),
    "exposed.copper_color": ((0.62, 0.36, 0.22), (0.85, 0.52, 0.36)),
    "exposed.tarnish": (0.1, 0.85),
    "exposed.metal_roughness": (0.2, 0.6),
    "exposed.normal_intensity": (0.8, 4.0),
    "patch_clouds.scale": (1.0, 3.0),
    "patch_mix.opacitymult": (0.3, 0.9),
    "runs.intensity": (8.0, 32.0),
    "runs_mix.opacitymult": (0.2, 0.7),
    "patina_mask.contrast": (0.5, 0.85),
    "metal_one.outputcolor": (1.0, 1.0),
    "crust_zero.outputcolor": (0.0, 0.0),
}
