"""Renders small glowing spheres at known points through cameras libcam wrote.

    blender -b --factory-startup -P render_points.py -- manifest.json

manifest.json: {"renders": [{"camera_script": "a.py", "output": "a.exr", "samples": 64,
                             "spheres": [[x, y, z, radius], ...]}, ...],
                "views": [{"camera_script": "b.py", "points": [[x, y, z], ...], "output": "b.json"}, ...]}

Each render sets the scene's camera by running libcam's script, then renders the spheres
(emission only, on black) with Cycles on the CPU: no denoising (Debian's Blender has no
OpenImageDenoise), the Standard view transform, a linear 32-bit EXR. Each view writes
Blender's own world_to_camera_view of the points (x, y in [0, 1] from the bottom left).
"""

import json
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector


def empty_scene():
    scene = bpy.context.scene
    for obj in list(scene.objects):
        if obj.type != "CAMERA":
            bpy.data.objects.remove(obj, do_unlink=True)
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    return scene


def glowing_material():
    material = bpy.data.materials.new("glow")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
    return material


def set_spheres(spheres, material):
    """The scene's spheres: these, and no others."""
    for obj in list(bpy.data.objects):
        if obj.name.startswith("sphere"):
            bpy.data.objects.remove(obj, do_unlink=True)
    for x, y, z, radius in spheres:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=radius, location=(x, y, z))
        sphere = bpy.context.active_object
        sphere.name = "sphere"
        sphere.data.materials.append(material)


def render_settings(scene):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0
    scene.cycles.use_adaptive_sampling = False
    # A one-pixel box filter: each pixel averages its own area, so a sphere's edge pixels
    # hold its coverage with less noise than the default wide filter at the same samples.
    scene.cycles.pixel_filter_type = "BOX"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.use_persistent_data = True


def set_camera(script):
    with open(script, encoding="utf-8") as file:
        exec(compile(file.read(), script, "exec"), {"__name__": "__main__"})


def main(manifest_path):
    with open(manifest_path, encoding="utf-8") as file:
        manifest = json.load(file)
    scene = empty_scene()
    material = glowing_material()
    render_settings(scene)
    for view in manifest.get("views", []):
        set_camera(view["camera_script"])
        bpy.context.view_layer.update()
        seen = [list(world_to_camera_view(scene, scene.camera, Vector(p))) for p in view["points"]]
        with open(view["output"], "w", encoding="utf-8") as file:
            json.dump(seen, file)
    for render in manifest.get("renders", []):
        set_spheres(render["spheres"], material)
        set_camera(render["camera_script"])
        scene.cycles.samples = render.get("samples", 64)
        scene.render.filepath = render["output"]
        bpy.ops.render.render(write_still=True)


main(sys.argv[sys.argv.index("--") + 1])
