"""The staging the Blender tests compare silhouettes in: an orthographic camera in front (-Y)
of a box, looking along +Y, and a plain white world. Imported by addon_test.py and
volume_import.py (their folder is put on sys.path)."""

import math

import bpy


def stage_front_view(scene, lo, hi):
    """Sets `scene`'s camera to an orthographic one framing the box `lo`..`hi` (metres, world
    axes) from the front, 1.2 times its largest side wide, and its world to white (strength
    1.5). Returns the camera object."""
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    size = max(b - a for a, b in zip(lo, hi))
    camera_data = bpy.data.cameras.new("front")
    camera_data.type = 'ORTHO'
    camera_data.ortho_scale = 1.2 * size
    camera = bpy.data.objects.new("front", camera_data)
    camera.location = (centre[0], centre[1] - 3 * size, centre[2])
    camera.rotation_euler = (math.pi / 2, 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.5
    scene.world = world
    return camera
