# Imports a glTF file with Blender's importer and prints what a user would look at: objects,
# each material's base colour source (vertex colours or an image texture), roughness (a
# value, or 'from a map' where the material map is wired to it),
# clearcoat and sheen, one piece's custom properties (its glTF node extras), the triangle count
# and the world bounding box.
# Usage (Debian 12: apt install blender python3-numpy):
#   blender -b --factory-startup --python scripts/check-blender-import.py -- FILE.glb
import sys

import numpy

numpy.bool = bool  # Debian's Blender 3.4 glTF importer still uses numpy.bool (packaging bug)
import bpy  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=sys.argv[sys.argv.index('--') + 1])
meshes = [o for o in bpy.data.objects if o.type == 'MESH']
print('objects', len(bpy.data.objects), 'meshes', len(meshes))
for mat in bpy.data.materials:
    if not mat.use_nodes:
        continue
    bsdf = next((n for n in mat.node_tree.nodes if n.type == 'BSDF_PRINCIPLED'), None)
    if bsdf is None:
        continue
    sources = [link.from_node.type for link in bsdf.inputs['Base Color'].links]
    rough = bsdf.inputs['Roughness']
    print('material', mat.name, 'base colour from', sources,
          'roughness', 'from a map' if rough.links else round(rough.default_value, 3),
          'clearcoat', round(bsdf.inputs['Clearcoat'].default_value, 3),
          'sheen', round(bsdf.inputs['Sheen'].default_value, 3))
print('images', len(bpy.data.images))
for o in meshes:
    if 'template' in o.keys():
        print('extras of', o.name, {k: o[k] for k in o.keys() if not k.startswith('_')})
        break
# Where the vertices landed (world space, metres): quantized files put each mesh's scale and
# offset in its object's transform, so these agree with the float file's within a micrometre.
corners = [o.matrix_world @ v.co for o in meshes for v in o.data.vertices]
if corners:
    lo = [round(min(c[k] for c in corners), 5) for k in range(3)]
    hi = [round(max(c[k] for c in corners), 5) for k in range(3)]
    print('triangles', sum(len(p.vertices) - 2 for o in meshes for p in o.data.polygons),
          'bounds', lo, hi)
