"""Benchmarks behind ``blender-match bench``: each module measures one capability and returns rows
of figures; the CLI prints them as a table. Speed and memory targets live here, not in tests."""
