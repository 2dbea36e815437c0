"""Running the matching pipeline out of Blender's process.

Blender's own Python has no torch, so the add-on starts ``python -m blender_match.worker`` with a
Python that has it (the backend), talks to it with the line protocol of ``protocol``, and polls it
from a timer (``client.WorkerJob``) so that Blender's interface never blocks. ``backend_setup``
creates that Python: a virtual environment with the worker's requirements.

``protocol``, ``client`` and ``backend_setup`` use only the standard library (Blender imports
them); ``__main__`` is the worker itself and imports the engine.
"""
