"""The package's version, in the foundation so that every floor (the worker's probe, the extension
builder) can read it without importing the add-on's entry point."""
__version__ = "0.1.0"
