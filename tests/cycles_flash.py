"""Blender's Cycles under ``FlashCamera``'s flash, for the tests that hold our renderer and the
Blender material against it (``tests/diffmat/test_render_cycles.py`` says why the scene is so).

The scene is a unit plane (UVs 0..1, u along +x) seen straight down by a perspective camera at the
camera distance whose horizontal field of view is ``fov``, a point light (radius 0) at the camera
or moved by a novel light's offset. Our flash of ``power`` p renders a white Lambertian sample's
centre at p, so its intensity is p pi d² (d the distance), which is Blender's point light of 4 pi
times that many watts. No world (its default grey would light the plane), no bounces (a plane lit
by a point light has only direct light), a 0.01-pixel filter (one point per pixel, at its centre,
as ours), a linear OpenEXR read back. The plane's own material is a Principled BSDF with the
single-scattering GGX and a UV Tangent node, without which Cycles ignores anisotropy.
"""
from __future__ import annotations

import math

import numpy as np
import torch

from blender_match.diffmat.render import FlashCamera, srgb_to_linear
from blender_match.vocabulary import ANISOTROPY_TANGENT_TURN

SIZE = 64
CAMERA = FlashCamera(power=0.25)  # a bright metal's highlight stays below 1, where our renderer clips
SAMPLES = 8


class CyclesFlash:
    """The scene of the module docstring; ``render`` gives the linear grey image, top row first."""

    def __init__(self, bpy, tmp_dir):
        self.bpy = bpy
        self.path = str(tmp_dir / "render.exr")
        bpy.ops.wm.read_factory_settings(use_empty=True)
        scene = bpy.context.scene
        scene.world = None
        scene.render.engine = "CYCLES"
        scene.cycles.device = "CPU"
        scene.cycles.samples = SAMPLES
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.use_denoising = False
        scene.cycles.max_bounces = 0
        scene.cycles.filter_width = 0.01
        scene.render.threads_mode = "FIXED"
        scene.render.threads = 1
        scene.render.resolution_x = scene.render.resolution_y = SIZE
        scene.render.resolution_percentage = 100
        scene.render.image_settings.file_format = "OPEN_EXR"
        scene.render.image_settings.color_depth = "32"
        scene.render.filepath = self.path
        bpy.ops.mesh.primitive_plane_add(size=1.0)
        self.plane = plane = bpy.context.active_object
        d = CAMERA.camera_distance()
        lens = bpy.data.cameras.new("flash camera")
        lens.sensor_fit = "HORIZONTAL"
        lens.angle = math.radians(CAMERA.fov)
        scene.camera = self._add(scene, bpy.data.objects.new("flash camera", lens), (0.0, 0.0, d))
        light = bpy.data.lights.new("flash", "POINT")
        light.shadow_soft_size = 0.0
        light.use_soft_falloff = False
        light.energy = 4 * math.pi * CAMERA.power * math.pi * d * d
        self.light = self._add(scene, bpy.data.objects.new("flash", light), (0.0, 0.0, d))
        material = bpy.data.materials.new("flat")
        plane.data.materials.append(material)
        tree = material.node_tree
        self.bsdf = tree.nodes["Principled BSDF"]
        self.bsdf.distribution = "GGX"
        tangent = tree.nodes.new("ShaderNodeTangent")
        tangent.direction_type = "UV_MAP"
        tree.links.new(tangent.outputs["Tangent"], self.bsdf.inputs["Tangent"])

    @staticmethod
    def _add(scene, obj, location):
        obj.location = location
        scene.collection.objects.link(obj)
        return obj

    def use(self, material):
        """Render ``material`` (a built one) instead of the plane's own."""
        self.plane.data.materials[0] = material

    def render(self, base, roughness, metallic, level, angle, light_offset=(0.0, 0.0)):
        """The plane's own material with flat values (base colour an sRGB grey, the angle the
        brushing's, as our maps hold it), the light at ``light_offset`` from the camera."""
        grey = float(srgb_to_linear(torch.tensor(base)))
        self.bsdf.inputs["Base Color"].default_value = (grey, grey, grey, 1.0)
        self.bsdf.inputs["Roughness"].default_value = roughness
        self.bsdf.inputs["Metallic"].default_value = metallic
        self.bsdf.inputs["Anisotropic"].default_value = level
        self.bsdf.inputs["Anisotropic Rotation"].default_value = (angle + ANISOTROPY_TANGENT_TURN) % 1.0
        return self.render_scene(light_offset)

    def render_scene(self, light_offset=(0.0, 0.0)):
        """The scene as it is, the light at ``light_offset`` from the camera."""
        bpy = self.bpy
        self.light.location = (*light_offset, CAMERA.camera_distance())
        bpy.ops.render.render(write_still=True)
        image = bpy.data.images.load(self.path, check_existing=False)
        try:
            image.colorspace_settings.name = "Non-Color"
            pixels = np.empty(SIZE * SIZE * 4, np.float32)
            image.pixels.foreach_get(pixels)
        finally:
            bpy.data.images.remove(image)
        return np.flipud(pixels.reshape(SIZE, SIZE, 4)[..., :3].mean(-1))


def highlight(image):
    """The highlight's long axis in degrees counter-clockwise from +x, in [0, 180), and the ratio
    of its long to its short axis: from the second moments about the centroid of the image above
    its darkest pixel."""
    w = image - image.min()
    w = w / w.sum()
    rows, cols = np.mgrid[0:SIZE, 0:SIZE] + 0.5
    x, y = cols - (w * cols).sum(), -(rows - (w * rows).sum())
    cov = np.array([[(w * x * x).sum(), (w * x * y).sum()], [(w * x * y).sum(), (w * y * y).sum()]])
    values, vectors = np.linalg.eigh(cov)
    return math.degrees(math.atan2(vectors[1, 1], vectors[0, 1])) % 180.0, math.sqrt(values[1] / values[0])
