"""The shared words: every material output once, and the anisotropy maps optional."""
from __future__ import annotations

from blender_match.vocabulary import (
    ANISOTROPY,
    ANISOTROPY_ANGLE,
    AUTHORED_USAGES,
    MATERIAL_OUTPUTS,
    OUTPUTS,
    PBR_USAGES,
    USAGES,
)


def test_each_output_is_named_after_its_substance_usage_in_lower_case():
    """The translator finds an output by its .sbs usage lower-cased, so no table can drift."""
    assert [o.name for o in MATERIAL_OUTPUTS] == [o.sbs_usage.lower() for o in MATERIAL_OUTPUTS]
    assert len(set(USAGES)) == len(USAGES) == len(MATERIAL_OUTPUTS)
    assert len({o.file for o in MATERIAL_OUTPUTS}) == len(MATERIAL_OUTPUTS)


def test_the_anisotropy_maps_are_optional_grey_data():
    level, angle = OUTPUTS[ANISOTROPY], OUTPUTS[ANISOTROPY_ANGLE]
    assert (level.sbs_usage, angle.sbs_usage) == ("anisotropyLevel", "anisotropyAngle")
    for output in (level, angle):
        assert (output.channels, output.file_channels, output.bits) == (1, 1, 8)
        assert output.colour_space == "Non-Color" and not output.srgb
        assert output.name not in PBR_USAGES and output.name not in AUTHORED_USAGES
