"""Sand: fine, dry sand with gentle wind ripples and visible grains (beige, grey or black sand).

Structure
- Ripples: a sawtooth ramp (Gradient Linear 1, several periods) is the asymmetric ripple profile:
  a long gentle windward slope and a short steep lee face. A directional warp across the crests,
  driven by two blended Perlin noises, makes the crests wavy and uneven; a slight blur rounds the
  lee face. Their strength fades in and out over the sample (a cloud mask), as real ripple fields do.
- Grains: a per-pixel white noise (one sand grain about a pixel at 512 px on a 30 cm sample) picks
  each grain's tone (dark mineral grains, plain grains, pale quartz); a finer cluster noise
  (BnW Spots 3) gives the grainy relief.
- Colour: the exposed sand colour times the exposed brightness, with the grains overlaid; ripple
  troughs slightly darker (heavy dark grains settle there), crests a little lighter.
- Height: ripples + broad undulation + grain; normal from it (OpenGL) combined with a per-grain
  detail normal, so the flash glints grain by grain. Roughness high (dry matte sand) around the
  exposed value, grains varying it. Metallic 0.

Exposed parameters
- ``sand_color`` (float3, sRGB): the sand's hue at full brightness (warm beige to neutral grey).
- ``brightness``: how light the sand is (1 pale beach sand, 0.15 black volcanic sand).
- ``ripples``: height of the wind ripples (0 flat, raked-smooth sand).
- ``grain``: contrast of the individual grains (fine uniform sand to coarse, mixed-mineral sand).
- ``roughness``: the mean roughness (lower for damp sand).
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    constant_map,
    gradient_over,
    keys_near,
    set_material_outputs,
)
from blender_match.library.expressions import const, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

GRAIN_TONES = [(0.0, (0.12, 0.12, 0.12)), (0.12, (0.36, 0.35, 0.34)), (0.3, (0.5, 0.5, 0.5)),
               (0.85, (0.55, 0.55, 0.54)), (1.0, (0.85, 0.84, 0.82))]
CLUSTER_TONES = [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.56, 0.56, 0.56))]
RIPPLE_TONES = [(0.0, (0.80, 0.80, 0.80)), (0.5, (0.92, 0.92, 0.92)), (1.0, (1.0, 1.0, 1.0))]
AO_TONES = [(0.0, (0.35, 0.35, 0.35)), (1.0, (1.0, 1.0, 1.0))]


def build() -> SbsGraph:
    g = SbsGraph("sand")
    g.expose("sand_color", (0.80, 0.70, 0.54), min=0.0, max=1.0)
    g.expose("brightness", 0.85, min=0.1, max=1.0)
    g.expose("ripples", 0.65, min=0.0, max=1.0)
    g.expose("grain", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.88, min=0.4, max=1.0)
    g.expose("relief", 0.6, min=0.0, max=1.0)
    ripples = get("ripples")
    grain = get("grain")

    # ---- ripples -------------------------------------------------------------------------------
    g.add("saw", "gradient_linear_1", tiling=6)
    g.add("wave_big", "perlin_noise", seed=71, scale=2.0)
    g.add("wave_small", "perlin_noise", seed=72, scale=5.0)
    g.add("wave", "blend", {"source": "wave_small", "destination": "wave_big"}, blendingmode=ADD_SUB,
          opacitymult=0.3)
    g.add("crests", "directionalwarp", {"input1": "saw", "inputintensity": "wave"}, intensity=40.0,
          warpangle=0.25)
    g.bind("crests", "warpangle", const(0.25).graph())  # across the crests, always
    g.add("crests_soft", "blur_hq_grayscale", {"source": "crests"}, intensity=2.5)
    g.add("field", "clouds_2", seed=73, scale=2.0)
    g.add("field_mask", "histogram_range", {"input": "field"}, range=0.7, position=0.6)
    g.add("ripple_h", "blend", {"source": "field_mask", "destination": "crests_soft"}, blendingmode=MULTIPLY,
          opacitymult=0.6)

    # ---- grains ----------------------------------------------------------------------------------
    g.add("grains", "white_noise")
    g.add("clusters", "bnw_spots_3", seed=74, scale=32.0)
    g.add("undulation", "clouds_1", seed=75, scale=2.0)

    # ---- height ------------------------------------------------------------------------------------
    g.add("ripple_level", "histogram_range", {"input": "ripple_h"}, range=0.5, position=0.5)
    g.bind("ripple_level", "range", lerp(0.0, 0.8, ripples).graph())
    g.add("h_undulate", "blend", {"source": "undulation", "destination": "ripple_level"}, blendingmode=ADD_SUB,
          opacitymult=0.15)
    g.add("h_clusters", "blend", {"source": "clusters", "destination": "h_undulate"}, blendingmode=ADD_SUB,
          opacitymult=0.025)
    g.add("height", "blend", {"source": "grains", "destination": "h_clusters"}, blendingmode=ADD_SUB,
          opacitymult=0.03)

    g.add("n_main", "normal", {"input1": "height"}, intensity=4.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(0.5, 8.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "grains"}, intensity=0.25, inversedy=True, input2alpha=False)
    g.add("normal", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.1, spreading=0.1,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------------
    g.add("sand_base", "uniform", outputcolor=(0.68, 0.60, 0.46, 1.0))
    g.bind("sand_base", "outputcolor",
           vector(get("sand_color", 3) * get("brightness"), 1.0).graph())
    gradient_over(g, "sand_grains", "grain_tones", "grains", GRAIN_TONES, "sand_base", blendingmode=OVERLAY,
                  opacitymult=0.5)
    g.bind("sand_grains", "opacitymult", lerp(0.15, 1.0, grain).graph())
    gradient_over(g, "sand_clusters", "cluster_tones", "clusters", CLUSTER_TONES, "sand_grains", blendingmode=OVERLAY,
                  opacitymult=0.6)
    gradient_over(g, "sand_ripples", "ripple_tones", "ripple_h", RIPPLE_TONES, "sand_clusters", blendingmode=MULTIPLY,
                  opacitymult=0.5)
    g.bind("sand_ripples", "opacitymult", lerp(0.0, 0.8, ripples).graph())
    gradient_over(g, "basecolor", "ao_color", "ao", AO_TONES, "sand_ripples", blendingmode=MULTIPLY, opacitymult=0.3)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "grains"}, range=0.1, position=0.88)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "clusters", "destination": "rough_base"}, blendingmode=ADD_SUB,
          opacitymult=0.05)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "ground"

SAMPLE_RANGES = {
    # hue only: the lightness comes from ``brightness`` (channels drawn one by one must stay sandy)
    "exposed.sand_color": ((0.76, 0.68, 0.54), (0.86, 0.76, 0.64)),
    "exposed.brightness": (0.15, 1.0),
    "exposed.ripples": (0.0, 1.0),
    "exposed.grain": (0.1, 0.9),
    "exposed.roughness": (0.7, 0.97),
    "exposed.relief": (0.2, 0.8),
    "crests.intensity": (25.0, 45.0),
    "wave_big.scale": (1.5, 3.0),
    "wave_small.scale": (4.0, 7.0),
    "field.scale": (1.5, 3.0),
    "undulation.scale": (1.5, 3.0),
    "crests_soft.intensity": (1.5, 4.0),
    "field_mask.position": (0.4, 0.8),
    "h_undulate.opacitymult": (0.0, 0.3),
    "grain_tones.colors": keys_near(GRAIN_TONES, 0.03),
    "ripple_tones.colors": keys_near(RIPPLE_TONES, 0.03),
    "ao_color.colors": keys_near(AO_TONES, 0.05),
    "cluster_tones.colors": keys_near(CLUSTER_TONES, 0.02),
    "n_grain.intensity": (0.1, 0.5),
}
