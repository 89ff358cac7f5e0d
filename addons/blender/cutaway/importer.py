"""Importing a cutaway glTF file: Blender's own glTF importer, then what it leaves undone
(see doc/blender.md)."""

import os
import warnings
from dataclasses import dataclass, field

import bpy

from . import hierarchy, materials, scene_setup
from .gltf_file import GltfFile


@dataclass
class ImportedFile:
    """What importing one file made."""

    root: bpy.types.Object = None  # the object of the scene's first node: the whole asset
    collection: bpy.types.Collection = None
    objects: list = field(default_factory=list)
    pieces: list = field(default_factory=list)
    lods: list = field(default_factory=list)
    collision_shapes: list = field(default_factory=list)
    backdrop: list = field(default_factory=list)  # the staging's objects (no shadows cast)
    translucent_materials: list = field(default_factory=list)
    camera: bpy.types.Object = None  # the file's camera, when it has one


def allow_numpy_bool():
    """Blender 3.4's glTF importer uses numpy.bool, which numpy 1.24 removed (Debian 12 ships
    the two together); alias it to bool where it is missing. A no-op elsewhere."""
    import numpy

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy 1.24 warns when asked for the removed alias
        if not hasattr(numpy, "bool"):
            numpy.bool = bool


def import_file(context, filepath, *, use_camera=True, use_sky=True, use_exposure=True):
    """Imports a cutaway .glb or .gltf into the context's scene and returns an ImportedFile.

    use_camera: the file's camera, if it has one, becomes the scene's camera.
    use_sky: a file that expects a sky (ambient_lux) gets it as the world's light.
    use_exposure: a file that gives its exposure is shown at it under the Standard view, with
        Cycles set to converge (scene_setup.use_converging_render).
    Raises OSError or ValueError for a file it cannot read (ValueError too for a
    `--compress meshopt` file, whose EXT_meshopt_compression Blender does not decode, and for
    a `--textures ktx2` file without its fallback),
    RuntimeError when Blender's importer fails.
    """
    gltf = GltfFile.load(filepath)
    if "EXT_meshopt_compression" in gltf.json.get("extensionsRequired", []):
        # Blender's glTF importer (3.4 to 4.x) has no meshopt decoder; say so plainly.
        raise ValueError(f"{os.path.basename(filepath)} was written with --compress meshopt, "
                         "which Blender cannot read: write it again with --compress quantize "
                         "(the default) or none")
    if "KHR_texture_basisu" in gltf.json.get("extensionsRequired", []):
        # Blender's glTF importer reads no KTX2: a file with the JPEG/PNG fallback imports.
        raise ValueError(f"{os.path.basename(filepath)} was written with --textures ktx2, "
                         "whose GPU textures Blender cannot read: write it again with "
                         "--texture-fallback (JPEG or PNG beside them) or --textures jpeg")
    before_objects = {o.as_pointer() for o in bpy.data.objects}
    before_materials = {m.as_pointer() for m in bpy.data.materials}
    before_images = {i.as_pointer() for i in bpy.data.images}
    allow_numpy_bool()
    if 'FINISHED' not in bpy.ops.import_scene.gltf(filepath=filepath):
        raise RuntimeError(f"Blender's glTF importer could not read {filepath}")
    new_objects = [o for o in bpy.data.objects if o.as_pointer() not in before_objects]
    new_materials = [m for m in bpy.data.materials if m.as_pointer() not in before_materials]
    new_images = [i for i in bpy.data.images if i.as_pointer() not in before_images]

    objects = hierarchy.match_nodes(gltf, new_objects)
    result = ImportedFile(objects=new_objects)
    result.lods = hierarchy.place_lods(gltf, objects)
    result.collision_shapes = hierarchy.hide_collision_shapes(new_objects)
    hierarchy.copy_missing_extras(gltf, objects)
    result.backdrop = scene_setup.stage_backdrop_and_lights(gltf, objects)
    pieces = hierarchy.piece_objects(gltf, objects)
    result.pieces = list(pieces)
    result.root = _root_object(gltf, objects)
    result.collection = hierarchy.collect(context, _asset_name(gltf), new_objects, pieces)
    result.translucent_materials = materials.add_translucency(gltf, new_materials, new_images)

    scene = context.scene
    camera_node = gltf.camera_node()
    if camera_node is not None and objects.get(camera_node) is not None:
        result.camera = objects[camera_node]
        if use_camera:
            scene_setup.use_camera(scene, result.camera, gltf.camera_aspect_ratio(camera_node))
    ambient_lux = gltf.ambient_lux()
    if use_sky and ambient_lux is not None:
        scene_setup.use_sky(scene, ambient_lux)
    exposure = gltf.exposure()
    if use_exposure and exposure is not None:
        scene_setup.use_exposure(scene, exposure)
        scene_setup.use_converging_render(scene)
    return result


def _root_object(gltf, objects):
    """The object of the scene's first node that is neither a camera nor a light."""
    for index in gltf.scene.get("nodes", []):
        node = gltf.nodes[index]
        if "camera" not in node and "KHR_lights_punctual" not in node.get("extensions", {}):
            return objects.get(index)
    return None


def _asset_name(gltf):
    name = gltf.scene.get("name")
    if not name:
        name = os.path.splitext(os.path.basename(gltf.path))[0]
    return name
