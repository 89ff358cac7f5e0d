"""Interior volumes: the OpenVDB file `cutaway volume` writes, imported to stand where Blender's
glTF importer puts the same object, with a material that shows its colour.

The volume is +Y up, like glTF (Blender is +Z up): Blender's glTF importer turns a glTF file
+90 degrees about X, so the volume object is turned the same way. Its grids are `density` (1
where solid, 0 outside) and `color` (linear RGB); Blender's volume shading reads neither without
a material, which left the fruit a faint grey haze.
"""

import math
import os

import bpy

# Extinction of the flesh per metre at density 1: a few millimetres of flesh are opaque, as on a
# cut face, while a thin slice still lets some light through.
FLESH_DENSITY = 400.0


def interior_material():
    """The material "cutaway interior": a Principled Volume whose density is the `density`
    grid times FLESH_DENSITY and whose colour is the `color` grid. Made once per file."""
    material = bpy.data.materials.get("cutaway interior")
    if material is not None:
        return material
    material = bpy.data.materials.new("cutaway interior")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    volume = nodes.new("ShaderNodeVolumePrincipled")
    volume.inputs["Density"].default_value = FLESH_DENSITY
    colour = nodes.new("ShaderNodeAttribute")
    colour.attribute_name = "color"
    material.node_tree.links.new(colour.outputs["Color"], volume.inputs["Color"])
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(volume.outputs["Volume"], output.inputs["Volume"])
    return material


def import_volume(context, path):
    """Imports the .vdb at `path` as a volume object turned +90 degrees about X (standing where
    the object's glTF stands when imported), with the interior material. Returns the object.
    Raises OSError when the file cannot be read as a volume."""
    if not os.path.isfile(path):
        raise OSError(f"{path}: no such file")
    before = set(bpy.data.objects)
    bpy.ops.object.volume_import(filepath=path, files=[{"name": os.path.basename(path)}],
                                 directory=os.path.dirname(os.path.abspath(path)) + os.sep)
    new = [o for o in bpy.data.objects if o not in before and o.type == 'VOLUME']
    if not new:
        raise OSError(f"{path}: Blender read no volume from it")
    obj = new[0]
    obj.data.grids.load()
    if obj.data.grids.error_message:
        raise OSError(f"{path}: {obj.data.grids.error_message}")
    obj.rotation_euler = (math.pi / 2, 0.0, 0.0)
    obj.data.materials.clear()
    obj.data.materials.append(interior_material())
    context.view_layer.update()
    return obj
