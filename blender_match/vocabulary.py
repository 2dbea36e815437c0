"""The words every floor of blender_match shares: material outputs, quality presets, devices,
progress stages and an automatic match's alternatives. Standard library only, so that Blender's
Python (which has no torch) reads the same definitions as the engine, the pipeline and the command
line.

A material output is one map a graph produces and a result folder holds: its name (the graph's
output usage, the report's key), its label, its Substance usage, how many channels the engine
produces, the PNG file it is written to (channels and bit depth) and the colour space Blender
reads that file in.

Brushed metals add two optional maps: the anisotropy level (0 isotropic, 1 fully anisotropic, on
Blender's Principled BSDF scale: the lobe's aspect is sqrt(1 - 0.9 level)) and the anisotropy angle,
the direction of the brushing (the grooves) in turns counter-clockwise from the texture's +u
towards +v. The highlight stretches across the grooves: Blender's "Anisotropic Rotation", glTF's
anisotropy direction and the tangent maps of Unreal and Unity are that angle plus a quarter turn
(``ANISOTROPY_TANGENT_TURN``).
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class MaterialOutput:
    """One map of a material (see the module docstring)."""

    name: str
    label: str
    sbs_usage: str
    channels: int
    file: str
    file_channels: int
    bits: int
    colour_space: str

    @property
    def srgb(self) -> bool:
        """True for colour stored sRGB-encoded (base colour), False for data maps."""
        return self.colour_space == "sRGB"


MATERIAL_OUTPUTS = (
    MaterialOutput("basecolor", "Base Color", "baseColor", 4, "basecolor.png", 3, 8, "sRGB"),
    MaterialOutput("normal", "Normal", "normal", 4, "normal.png", 3, 16, "Non-Color"),
    MaterialOutput("roughness", "Roughness", "roughness", 1, "roughness.png", 1, 8, "Non-Color"),
    MaterialOutput("metallic", "Metallic", "metallic", 1, "metallic.png", 1, 8, "Non-Color"),
    MaterialOutput("height", "Height", "height", 1, "height.png", 1, 16, "Non-Color"),
    MaterialOutput("ambientocclusion", "Ambient Occlusion", "ambientOcclusion", 1, "ambientocclusion.png", 1, 8,
                   "Non-Color"),
    MaterialOutput("anisotropylevel", "Anisotropy", "anisotropyLevel", 1, "anisotropylevel.png", 1, 8, "Non-Color"),
    MaterialOutput("anisotropyangle", "Anisotropy Angle", "anisotropyAngle", 1, "anisotropyangle.png", 1, 8,
                   "Non-Color"),
)
OUTPUTS = {output.name: output for output in MATERIAL_OUTPUTS}
USAGES = tuple(OUTPUTS)
# the maps every physically based material has (exports require them); the others may be absent
PBR_USAGES = ("basecolor", "normal", "roughness", "metallic")
# the maps a library material is authored with and compared on (ambient occlusion is derived)
AUTHORED_USAGES = (*PBR_USAGES, "height")
# the anisotropic lobe's maps, optional: a graph without them renders an isotropic lobe
ANISOTROPY, ANISOTROPY_ANGLE = "anisotropylevel", "anisotropyangle"
# from the brushing direction (the angle map) to the direction the highlight stretches along, which
# Blender's "Anisotropic Rotation", glTF and the game engines' tangents name: a quarter turn
ANISOTROPY_TANGENT_TURN = 0.25


@dataclass(frozen=True)
class Choice:
    """A named choice a user makes: its name (the value on the command line and in requests), the
    label Blender shows and a one-line description."""

    name: str
    label: str
    description: str


QUALITIES = (
    Choice("draft", "Draft", "Fast: a short fit, for a first look"),
    Choice("balanced", "Balanced", "The default: a good fit in a few minutes"),
    Choice("best", "Best", "The longest fit, for the final material"),
)
QUALITY_NAMES = tuple(q.name for q in QUALITIES)
DEFAULT_QUALITY = "balanced"

DEVICES = (
    Choice("auto", "Automatic", "A GPU (CUDA or Metal) when the worker has one, else the CPU"),
    Choice("cpu", "CPU", "The processor"),
    Choice("cuda", "CUDA", "An NVIDIA GPU"),
    Choice("mps", "Metal", "An Apple GPU"),
)
DEVICE_NAMES = tuple(d.name for d in DEVICES)
DEFAULT_DEVICE = "auto"

# The files of a result folder besides the maps (``MaterialOutput.file``).
PARAMS_FILE, COMPARISON_FILE, REPORT_FILE = "params.json", "comparison.png", "report.json"
# How a fitted material meets its photo: a graph-level parameter set of that name holds the base
# colour's gain and the zoom (texture periods across the photo); params.json names them
# "calibration.basecolor_gain" and "calibration.zoom", report.json's "calibration" object the same,
# with the photo's flash falloff beside them (a property of the photo: no map or parameter has it).
CALIBRATION, GAIN, ZOOM, FALLOFF = "calibration", "basecolor_gain", "zoom", "falloff"

# The stages of a match, in order, as progress events name them ("selecting" only without a graph).
READING_PHOTO, SELECTING, FITTING, WRITING_MAPS = "reading photo", "selecting", "fitting", "writing maps"
STAGES = (READING_PHOTO, SELECTING, FITTING, WRITING_MAPS)
STAGE_TITLES = {stage: stage.capitalize() for stage in STAGES}


# An automatic match's alternatives: the graphs its ranking put next after the one it kept, so
# that with it they are the ranking's top 3 (the panel's and the command line's "also close")
ALTERNATIVES = 2


def ranked_alternatives(report: dict) -> list[str]:
    """The graphs an automatic match's report ranks next after the one it kept (at most
    ``ALTERNATIVES``); none for a named match, whose report has no ranking."""
    kept = report.get("graph")
    ranked = [e.get("graph") for e in report.get("ranking") or () if isinstance(e, dict)]
    return [name for name in ranked if isinstance(name, str) and name != kept][:ALTERNATIVES]
