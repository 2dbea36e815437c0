"""Gravel: loose, packed rounded pebbles (about 0.5-3 cm) of mixed grey, brown and beige stone.

Structure
- Stones: two Tile Samplers of elongated paraboloids (random position, rotation and size, high
  scale so neighbours overlap and pack): a layer of large pebbles on top and a denser layer of small
  ones lying lower, which fills the spaces between the large ones (max blend). Both are bent a
  little by a noise warp so the outlines are not perfect ellipses.
- Stone identity: for each layer a twin Tile Sampler with the same seed and layout but flat discs of
  fully random luminance gives every pebble its own value; it picks the pebble's colour in a
  stone palette (dark basalt, grey, beige, brown, pale quartz) and shifts its roughness.
- Gaps: where neither layer reaches, a dark, fine, gritty bed shows (the shadowed soil between the
  stones); ambient occlusion darkens the contacts.
- Colour: the palette multiplies the exposed stone colour (how strongly: exposed
  ``variation``), then speckled (stone grain) and mottled; the gaps take a dark version of it.
- Height: pebble domes plus a fine grain; normal from it (OpenGL) combined with a grain detail
  normal. Roughness: stones semi-rough around the exposed value, gaps fully rough. Metallic 0.

Exposed parameters
- ``stone_color`` (float3, sRGB): the colour of the lightest stones; the palette darkens and tints
  it per pebble.
- ``variation``: how different the pebbles are from one another (0 all one stone, 1 very mixed).
- ``packing``: how tightly the pebbles fill the surface (low: separated stones in dark grit).
- ``gap_darkness``: how dark and deep the spaces between the stones are.
- ``roughness``: the stones' mean roughness (polished river pebbles low, crushed stone high).
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    COPY,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    constant_map,
    gradient_keys,
    set_material_outputs,
)
from blender_match.library.expressions import const, get, lerp, minimum, vector
from blender_match.translator.runtime import SbsGraph

# pebble tones, multiplied onto the stone colour (1 keeps it): every pebble a different rock
STONE_TONES = [
    (0.0, (0.22, 0.22, 0.23)),   # dark basalt
    (0.18, (0.45, 0.45, 0.46)),  # dark grey
    (0.38, (0.66, 0.66, 0.66)),  # grey
    (0.55, (0.88, 0.79, 0.66)),  # beige
    (0.70, (0.70, 0.54, 0.40)),  # brown
    (0.85, (0.90, 0.89, 0.87)),  # light grey
    (1.0, (1.0, 0.98, 0.95)),    # pale quartz
]
MOTTLE_TONES = [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.58, 0.57, 0.55))]
SPECKLE_TONES = [(0.0, (0.30, 0.30, 0.30)), (0.5, (0.5, 0.5, 0.5)), (1.0, (0.70, 0.69, 0.67))]
AO_TONES = [(0.0, (0.15, 0.15, 0.15)), (1.0, (1.0, 1.0, 1.0))]


def build() -> SbsGraph:
    g = SbsGraph("gravel")
    g.expose("stone_color", (0.76, 0.73, 0.69), min=0.0, max=1.0)
    g.expose("variation", 0.75, min=0.0, max=1.0)
    g.expose("packing", 0.6, min=0.0, max=1.0)
    g.expose("gap_darkness", 0.6, min=0.0, max=1.0)
    g.expose("roughness", 0.62, min=0.2, max=1.0)
    g.expose("relief", 0.6, min=0.0, max=1.0)
    packing = get("packing")
    gaps = get("gap_darkness")

    # ---- pebble layers -------------------------------------------------------------------------
    large = dict(seed=61, x_amount=8, y_amount=8, scale=2.0, size_xy=(1.0, 0.72), position_random=0.5,
                 rotation_random=0.5, scale_random=0.55)
    small = dict(seed=62, x_amount=18, y_amount=18, scale=2.0, size_xy=(1.0, 0.75), position_random=0.5,
                 rotation_random=0.5, scale_random=0.5)
    g.add("peb_l", "tile_sampler", pattern=3, luminance_random=0.2, **large)
    g.add("id_l", "tile_sampler", pattern=2, luminance_random=1.0, **large)
    g.add("peb_s", "tile_sampler", pattern=3, luminance_random=0.3, **small)
    g.add("id_s", "tile_sampler", pattern=2, luminance_random=1.0, **small)
    for node, lo, hi in (("peb_l", 1.3, 2.3), ("id_l", 1.3, 2.3), ("peb_s", 1.5, 2.4), ("id_s", 1.5, 2.4)):
        # capped at the Tile Sampler's scale maximum (2): a bound value above it is clamped by the
        # engine on the source node but widens the slider of the translated one (exported default)
        g.bind(node, "scale", minimum(lerp(lo, hi, packing), 2.0).graph())
        # a pebble and its identity twin must keep one layout: pin the layout parameters
        layout = large if node.endswith("_l") else small
        for param in ("position_random", "rotation_random", "scale_random", "size_xy"):
            g.bind(node, param, const(layout[param]).graph())
        for param in ("offset", "rotation", "mask_random"):
            g.bind(node, param, const(0.0).graph())
    g.bind("id_l", "luminance_random", const(1.0).graph())
    g.bind("id_s", "luminance_random", const(1.0).graph())

    # the same gentle warp for the shapes and their identities, so they stay registered
    g.add("bend", "perlin_noise", seed=63, scale=12.0)
    for node in ("peb_l", "id_l", "peb_s", "id_s"):
        g.add(f"{node}_w", "warp", {"input1": node, "inputgradient": "bend"}, intensity=0.35)
        g.bind(f"{node}_w", "intensity", const(0.35).graph())

    # ---- height --------------------------------------------------------------------------------
    g.add("grit", "bnw_spots_3", seed=64, scale=16.0)
    g.add("grit_low", "histogram_range", {"input": "grit"}, range=0.12, position=0.08)
    g.add("small_low", "histogram_range", {"input": "peb_s_w"}, range=0.5, position=0.27)
    g.add("h_small", "blend", {"source": "small_low", "destination": "grit_low"}, blendingmode=MAX)
    g.add("h_stones", "blend", {"source": "peb_l_w", "destination": "h_small"}, blendingmode=MAX)
    g.add("speckle", "bnw_spots_3", seed=65, scale=32.0)
    g.add("h_grain", "blend", {"source": "speckle", "destination": "h_stones"}, blendingmode=SUBTRACT,
          opacitymult=0.03)
    g.add("height", "histogram_range", {"input": "h_grain"}, range=1.0, position=0.5)

    # masks: where the large layer wins, and where any stone covers
    g.add("large_over", "blend", {"source": "small_low", "destination": "peb_l_w"}, blendingmode=SUBTRACT)
    g.add("large_mask", "histogram_scan", {"input_1": "large_over"}, position=0.97, contrast=0.9)
    g.add("cover", "histogram_scan", {"input_1": "h_stones"}, position=0.85, contrast=0.6)
    g.bind("cover", "position", lerp(0.92, 0.8, gaps).graph())

    # ---- normal and occlusion -----------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "height"}, intensity=6.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(1.0, 12.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "speckle"}, intensity=0.5, inversedy=True, input2alpha=False)
    g.add("normal", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.25, spreading=0.08,
          model=OUR_OCCLUSION)

    # ---- colour --------------------------------------------------------------------------------
    g.add("tones_l", "gradient", {"input1": "id_l_w"}, **gradient_keys(STONE_TONES))
    g.add("tones_s", "gradient", {"input1": "id_s_w"}, **gradient_keys(STONE_TONES))
    g.add("tones", "blend", {"source": "tones_l", "destination": "tones_s", "opacity": "large_mask"},
          blendingmode=COPY)
    g.add("stone_base", "uniform", outputcolor=(0.76, 0.73, 0.69, 1.0))
    g.bind("stone_base", "outputcolor", vector(get("stone_color", 3), 1.0).graph())
    g.add("stones_varied", "blend", {"source": "tones", "destination": "stone_base"},
          blendingmode=MULTIPLY, opacitymult=0.75)
    g.bind("stones_varied", "opacitymult", get("variation").graph())
    g.add("mottle", "clouds_2", seed=66, scale=6.0)
    g.add("mottle_tones", "gradient", {"input1": "mottle"}, **gradient_keys(MOTTLE_TONES))
    g.add("stones_mottled", "blend", {"source": "mottle_tones", "destination": "stones_varied"},
          blendingmode=SOFT_LIGHT, opacitymult=0.8)
    g.add("speckle_tones", "gradient", {"input1": "speckle"}, **gradient_keys(SPECKLE_TONES))
    g.add("stones_speckled", "blend", {"source": "speckle_tones", "destination": "stones_mottled"},
          blendingmode=OVERLAY, opacitymult=0.3)
    g.add("gap_tint", "uniform", outputcolor=(0.32, 0.30, 0.28, 1.0))
    g.bind("gap_tint", "outputcolor",
           vector(lerp(0.55, 0.12, gaps), lerp(0.52, 0.11, gaps), lerp(0.48, 0.10, gaps), 1.0).graph())
    g.add("gap_col", "blend", {"source": "gap_tint", "destination": "stones_mottled"}, blendingmode=MULTIPLY)
    g.add("gap_grit", "blend", {"source": "speckle_tones", "destination": "gap_col"}, blendingmode=OVERLAY,
          opacitymult=0.6)
    g.add("bed", "blend", {"source": "stones_speckled", "destination": "gap_grit", "opacity": "cover"},
          blendingmode=COPY)
    g.add("ao_color", "gradient", {"input1": "ao"}, **gradient_keys(AO_TONES))
    g.add("basecolor", "blend", {"source": "ao_color", "destination": "bed"}, blendingmode=MULTIPLY,
          opacitymult=0.5)
    g.bind("basecolor", "opacitymult", lerp(0.2, 0.8, gaps).graph())

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_id", "blend", {"source": "id_l_w", "destination": "id_s_w", "opacity": "large_mask"},
          blendingmode=COPY)
    g.add("rough_stones", "histogram_range", {"input": "rough_id"}, range=0.2, position=0.62)
    g.bind("rough_stones", "position", get("roughness").graph())
    g.add("rough_gaps", "uniform", colorswitch=False, outputcolor=(0.95, 0.95, 0.95, 1.0))
    g.add("roughness", "blend", {"source": "rough_stones", "destination": "rough_gaps", "opacity": "cover"},
          blendingmode=COPY)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "ground"

def _near(stops, d: float) -> tuple:
    """Per-key colour ranges of a gradient: each key's colour +- d (the palette keeps its hues)."""
    lo = [max(0.0, c - d) if i % 4 < 3 else 1.0 for i, c in enumerate(gradient_keys(stops)["colors"])]
    hi = [min(1.0, c + d) if i % 4 < 3 else 1.0 for i, c in enumerate(gradient_keys(stops)["colors"])]
    return lo, hi


SAMPLE_RANGES = {
    "exposed.stone_color": ((0.70, 0.66, 0.58), (0.82, 0.77, 0.68)),
    "exposed.variation": (0.3, 1.0),
    "exposed.packing": (0.3, 1.0),
    "exposed.gap_darkness": (0.3, 0.9),
    "exposed.roughness": (0.45, 0.85),
    "exposed.relief": (0.3, 1.0),
    "bend.scale": (8.0, 14.0),
    "mottle.scale": (4.0, 8.0),
    "grit.scale": (12.0, 20.0),
    "small_low.position": (0.2, 0.35),
    "tones_l.colors": _near(STONE_TONES, 0.04),
    "tones_s.colors": _near(STONE_TONES, 0.04),
    "mottle_tones.colors": _near(MOTTLE_TONES, 0.03),
    "speckle_tones.colors": _near(SPECKLE_TONES, 0.03),
    "ao_color.colors": _near(AO_TONES, 0.05),
    "n_grain.intensity": (0.2, 1.0),
    "peb_l.luminance_random": (0.0, 0.4),
    "stones_mottled.opacitymult": (0.3, 1.0),
    "stones_speckled.opacitymult": (0.15, 0.7),
}
