"""Writing files safely (``safe_files``): JSON text ends in a newline and an existing file is
replaced only when the caller says so."""
from __future__ import annotations

import json

import pytest

from blender_match.safe_files import FileWriteError, write_json_atomic


def test_json_is_indented_and_ends_in_a_newline(tmp_path):
    path = tmp_path / "meta.json"
    write_json_atomic(path, {"graph": "leather", "params": [1, 2]})
    text = path.read_text(encoding="utf-8")
    assert text == json.dumps({"graph": "leather", "params": [1, 2]}, indent=1) + "\n"


def test_json_refuses_to_replace_a_file_unless_told(tmp_path):
    path = tmp_path / "meta.json"
    path.write_text("keep", encoding="utf-8")
    with pytest.raises(FileWriteError, match="meta.json: already exists"):
        write_json_atomic(path, {"a": 1})
    assert path.read_text(encoding="utf-8") == "keep"
    write_json_atomic(path, {"a": 1}, overwrite=True)
    assert json.loads(path.read_text(encoding="utf-8")) == {"a": 1}
