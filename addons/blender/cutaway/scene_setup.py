"""The scene around the imported objects: its camera, the sky as the world's light, and the
exposure that shows the file's lights as cutaway means them.

Units: Blender's glTF importer turns a light of E lux into a sun of E / 683 W/m2. A world
background of strength W lights an open surface with pi * W W/m2, so a sky of A lux is a
background of strength A / (683 pi). A file's exposure X (display value per unit of radiance
in three.js, whose lights are in lux) is 683 X in Blender's units, i.e. log2(683 X) stops under
the Standard view.
"""

import math

import bpy

LUMENS_PER_WATT = 683.0
WORLD_NAME = "cutaway sky"


def use_camera(scene, camera, aspect_ratio=None):
    """Makes `camera` the scene's camera and, when the file gives a sensible aspect ratio,
    fits the render's height to it (keeping its width)."""
    scene.camera = camera
    if aspect_ratio is not None and 0.1 <= aspect_ratio <= 10:
        render = scene.render
        render.pixel_aspect_x = render.pixel_aspect_y = 1.0
        render.resolution_y = max(1, round(render.resolution_x / aspect_ratio))


def world_strength(ambient_lux):
    """The strength of a uniform world background that gives `ambient_lux` on an open
    surface."""
    return ambient_lux / (LUMENS_PER_WATT * math.pi)


def use_sky(scene, ambient_lux):
    """Lights the scene with a uniform white world of `ambient_lux` lux. Returns the world."""
    world = bpy.data.worlds.get(WORLD_NAME) or bpy.data.worlds.new(WORLD_NAME)
    world.use_nodes = True
    tree = world.node_tree
    background = next((n for n in tree.nodes if n.type == 'BACKGROUND'), None)
    if background is None:
        background = tree.nodes.new("ShaderNodeBackground")
    output = next((n for n in tree.nodes if n.type == 'OUTPUT_WORLD'), None)
    if output is None:
        output = tree.nodes.new("ShaderNodeOutputWorld")
    for link in list(background.inputs["Color"].links):
        tree.links.remove(link)
    background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    background.inputs["Strength"].default_value = world_strength(ambient_lux)
    tree.links.new(background.outputs["Background"], output.inputs["Surface"])
    scene.world = world
    return world


def use_exposure(scene, exposure):
    """Shows the scene under the Standard view at the file's exposure (see the module's
    units)."""
    view = scene.view_settings
    view.view_transform = 'Standard'
    view.look = 'None'
    view.gamma = 1.0
    view.exposure = math.log2(exposure * LUMENS_PER_WATT)


# Cycles sampling under which a cutaway scene's frame converges (doc/lighting.md, Blender): adaptive
# sampling stops a pixel once its noise is under ADAPTIVE_THRESHOLD, between ADAPTIVE_MIN_SAMPLES
# and MAX_SAMPLES samples.
ADAPTIVE_THRESHOLD = 0.01
ADAPTIVE_MIN_SAMPLES = 64
MAX_SAMPLES = 1024


def denoiser_available():
    """True when this Blender's Cycles was built with OpenImageDenoise (Debian 12's is not)."""
    try:
        import _cycles
    except ImportError:
        return False
    return bool(getattr(_cycles, "with_openimagedenoise", False))


def use_converging_render(scene):
    """Sets Cycles up so that a render of a cutaway scene converges: adaptive sampling (see the
    constants), the denoiser where the build has one, and no caustics from the flesh's clear
    coat with glossy blur 1 (the speckles of a short render are those paths, not the lighting).
    Eevee's samples are left at Blender's default (64)."""
    cycles = scene.cycles
    cycles.use_adaptive_sampling = True
    cycles.adaptive_threshold = ADAPTIVE_THRESHOLD
    cycles.adaptive_min_samples = ADAPTIVE_MIN_SAMPLES
    cycles.samples = MAX_SAMPLES
    cycles.caustics_reflective = False
    cycles.caustics_refractive = False
    cycles.blur_glossy = 1.0
    cycles.use_denoising = denoiser_available()
    if cycles.use_denoising:
        cycles.denoiser = 'OPENIMAGEDENOISE'


def stage_backdrop_and_lights(gltf, objects):
    """Gives the file's staging what glTF cannot say (doc/lighting.md): the backdrop (a node
    whose extras say `backdrop`, and the objects below it) casts no shadow, since the studio's
    lights stand inside the sweep; each sun takes its source's size from its node's extras
    (`angle_deg`, Blender's sun angle), so shadows are as soft as in the other renderers.
    `objects` maps node indices to the imported objects. Returns the backdrop's objects."""
    import math

    backdrop = []
    for index, obj in objects.items():
        extras = gltf.nodes[index].get("extras")
        if not isinstance(extras, dict):
            continue
        if extras.get("backdrop") is True:
            backdrop += [obj] + list(obj.children_recursive)
        angle = extras.get("angle_deg")
        if obj.type == 'LIGHT' and obj.data.type == 'SUN' and isinstance(angle, (int, float)):
            obj.data.angle = math.radians(min(max(float(angle), 0.0), 180.0))
    for obj in backdrop:
        obj.visible_shadow = False
    return backdrop

