"""The type codes of a Substance ``.sbs`` document (a ``paraminput``'s, a function node's type):
the one table that the translator (reading) and ``library.sbs_export`` (writing) share.

Standard library only.
"""
from __future__ import annotations

# type code -> (kind, components)
TYPE_CODES = {
    4: ("bool", 1), 16: ("int", 1), 32: ("int", 2), 64: ("int", 3), 128: ("int", 4),
    256: ("float", 1), 512: ("float", 2), 1024: ("float", 3), 2048: ("float", 4), 16384: ("string", 1),
}
CODE_OF = {kind_n: code for code, kind_n in TYPE_CODES.items()}


def type_code(kind: str, components: int = 1) -> int:
    """The type code of a value of ``kind`` ("bool", "int", "float", "string") with ``components``."""
    return CODE_OF[(kind, components)]
