"""Reading an .sbs document safely: a size cap, no DTD, no entities, no network, no huge trees.

A .sbs file is plain XML without a document type declaration, so any DOCTYPE (the carrier of
external entities and entity-expansion bombs) is refused before parsing; the lxml parser is also
configured not to resolve entities, load DTDs or touch the network, in case one slips through.
"""
from __future__ import annotations

import os
import re

from lxml import etree

from .errors import TranslatorError

MAX_BYTES = 64 * 1024 * 1024
MAX_ELEMENTS = 2_000_000
_DOCTYPE = re.compile(rb"<!\s*(DOCTYPE|ENTITY)", re.IGNORECASE)


def _parser() -> etree.XMLParser:
    return etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False, load_dtd=False,
                           dtd_validation=False, remove_comments=True, remove_pis=True, collect_ids=False)


def read_bytes(path, max_bytes: int = MAX_BYTES) -> bytes:
    """The file's bytes, refusing files over ``max_bytes``."""
    try:
        size = os.path.getsize(path)
        if size > max_bytes:
            raise TranslatorError(path, f"document is too large ({size} bytes; the limit is {max_bytes})")
        with open(path, "rb") as fh:
            data = fh.read(max_bytes + 1)
    except TranslatorError:
        raise
    except OSError as exc:
        raise TranslatorError(path, f"cannot read the file ({exc.strerror or exc})") from None
    if len(data) > max_bytes:
        raise TranslatorError(path, f"document is too large (more than {max_bytes} bytes)")
    return data


def parse_bytes(data: bytes, name, max_bytes: int = MAX_BYTES) -> etree._Element:
    """Parse ``data`` as a Substance package; TranslatorError for anything unsafe or malformed."""
    if not isinstance(data, (bytes, bytearray)):
        raise TranslatorError(name, "expected the document's bytes")
    if len(data) > max_bytes:
        raise TranslatorError(name, f"document is too large ({len(data)} bytes; the limit is {max_bytes})")
    head = bytes(data)
    if _DOCTYPE.search(head) or _DOCTYPE.search(head.replace(b"\x00", b"")):
        raise TranslatorError(name, "document type declarations and entities are not allowed in .sbs files")
    if not head.strip():
        raise TranslatorError(name, "empty document")
    try:
        root = etree.fromstring(head, _parser())
    except etree.XMLSyntaxError as exc:
        raise TranslatorError(name, f"malformed XML ({exc})") from None
    except (ValueError, etree.LxmlError) as exc:
        raise TranslatorError(name, f"unreadable XML ({exc})") from None
    if root is None:
        raise TranslatorError(name, "empty document")
    tree = root.getroottree()
    if tree.docinfo.doctype or tree.docinfo.internalDTD is not None:
        raise TranslatorError(name, "document type declarations are not allowed in .sbs files")
    count = 0
    for el in root.iter():
        count += 1
        if not isinstance(el.tag, str):
            raise TranslatorError(name, "entity references are not allowed in .sbs files")
        if count > MAX_ELEMENTS:
            raise TranslatorError(name, f"document has more than {MAX_ELEMENTS} elements")
    if root.tag != "package":
        raise TranslatorError(name, f"not a Substance package (root element {str(root.tag)[:40]!r})")
    return root


def read_document(path, max_bytes: int = MAX_BYTES) -> etree._Element:
    """Read and parse the .sbs file at ``path``."""
    return parse_bytes(read_bytes(path, max_bytes), path, max_bytes)
