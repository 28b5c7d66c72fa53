"""The scene of the README's Blender picture, built around the scene's camera.

    blender -b --factory-startup -P plan/render.py -P docs/images/blender_scene.py \
        -o render_ -F PNG -f 1 -- points.txt

Run after the script that sets the camera (libcam render-plan's render.py): a floor of
glowing checks 1.2 m below the camera, and glowing spheres on a ring around it, from
straight ahead to past its sides, placed in the camera's own frame (Blender's: looking
along -Z, +Y up). Writes the spheres' centres in world coordinates, one "x,y,z" per line,
to the file named after "--", for libcam project.
"""

import math
import sys

import bpy
from mathutils import Matrix, Vector

scene = bpy.context.scene
camera = scene.camera
to_world = camera.matrix_world.copy()

for obj in list(scene.objects):
    if obj.type != "CAMERA":
        bpy.data.objects.remove(obj, do_unlink=True)
world = scene.world or bpy.data.worlds.new("World")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.02, 0.025, 0.04, 1)


def glowing(name, colour=None, checker=False):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    if checker:
        texture = nodes.new("ShaderNodeTexChecker")
        texture.inputs["Scale"].default_value = 24.0
        texture.inputs["Color1"].default_value = (0.55, 0.55, 0.5, 1)
        texture.inputs["Color2"].default_value = (0.08, 0.08, 0.1, 1)
        links.new(texture.outputs["Color"], emission.inputs["Color"])
    else:
        emission.inputs["Color"].default_value = colour
    emission.inputs["Strength"].default_value = 1.0
    return material


# The floor: a plane across the camera's view, 1.2 m below it.
bpy.ops.mesh.primitive_plane_add(size=12.0)
floor = bpy.context.active_object
floor.matrix_world = to_world @ Matrix.Translation((0, -1.2, 0)) @ Matrix.Rotation(math.pi / 2, 4, "X")
floor.data.materials.append(glowing("floor", checker=True))

# Spheres 3 m away, every 30 degrees round from straight ahead, at three heights.
colours = [(1.0, 0.25, 0.2, 1), (1.0, 0.8, 0.2, 1), (0.3, 0.9, 0.35, 1), (0.25, 0.6, 1.0, 1), (0.8, 0.35, 1.0, 1)]
centres = []
for row, elevation in enumerate((-20.0, 5.0, 30.0)):
    for column, azimuth in enumerate(range(-90, 91, 30)):
        a, e = math.radians(azimuth), math.radians(elevation)
        direction = Vector((math.sin(a) * math.cos(e), math.sin(e), -math.cos(a) * math.cos(e)))
        centre = to_world @ (3.0 * direction)
        bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.16, location=centre)
        sphere = bpy.context.active_object
        sphere.data.materials.append(glowing("sphere", colours[(row + column) % len(colours)]))
        centres.append(centre)

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 32
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0
scene.view_settings.view_transform = "Standard"

with open(sys.argv[sys.argv.index("--") + 1], "w", encoding="utf-8") as file:
    for c in centres:
        file.write(f"{c.x!r},{c.y!r},{c.z!r}\n")
