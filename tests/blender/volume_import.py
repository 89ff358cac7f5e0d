# Imports an interior volume's .vdb into Blender as a user would (File > Import > OpenVDB),
# turned +90 degrees about X as Blender's glTF importer turns the whole-object glTF (the volume
# is +Y up, like glTF and Houdini; Blender is +Z up), and prints one JSON line with what Blender
# read: the grids with their types, the volume object's world bounding box (metres, Blender's
# axes), and, with --render PNG, renders it with Blender's default
# volume shading (Principled Volume reading "density" and "color") from the front, so that a
# person can look at the fruit's interior as a translucent cloud.
# Usage: blender -b --factory-startup --python tests/blender/volume_import.py -- FILE.vdb
#        [--render OUT.png]
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from front_view import stage_front_view  # noqa: E402  (after its folder is on the path)

args = sys.argv[sys.argv.index('--') + 1:]
path = args[0]
render = args[args.index('--render') + 1] if '--render' in args else None

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.object.volume_import(filepath=path, files=[{'name': path.split('/')[-1]}],
                             directory=path.rsplit('/', 1)[0] + '/')
volumes = [o for o in bpy.data.objects if o.type == 'VOLUME']
report = {'volumes': len(volumes), 'grids': {}, 'bounds': None}
if volumes:
    obj = volumes[0]
    obj.rotation_euler = (1.5707963267948966, 0, 0)
    grids = obj.data.grids
    grids.load()
    report['grids'] = {g.name: g.data_type for g in grids}
    report['load_error'] = grids.error_message
    bpy.context.view_layer.update()
    corners = [obj.matrix_world @ __import__('mathutils').Vector(c) for c in obj.bound_box]
    report['bounds'] = [[min(c[k] for c in corners) for k in range(3)],
                        [max(c[k] for c in corners) for k in range(3)]]
    if render:
        scene = bpy.context.scene
        mat = bpy.data.materials.new('interior')
        mat.use_nodes = True
        nodes = mat.node_tree.nodes
        nodes.clear()
        volume = nodes.new('ShaderNodeVolumePrincipled')
        volume.inputs['Density'].default_value = 400.0  # metres: a few mm of flesh is opaque
        colour = nodes.new('ShaderNodeAttribute')
        colour.attribute_name = 'color'
        mat.node_tree.links.new(colour.outputs['Color'], volume.inputs['Color'])
        out = nodes.new('ShaderNodeOutputMaterial')
        mat.node_tree.links.new(volume.outputs['Volume'], out.inputs['Volume'])
        obj.data.materials.append(mat)
        stage_front_view(scene, *report['bounds'])
        scene.render.engine = 'CYCLES'
        scene.cycles.samples = 16
        scene.cycles.use_denoising = False
        scene.cycles.device = 'CPU'
        scene.render.resolution_x = scene.render.resolution_y = 256
        scene.render.filepath = render
        bpy.ops.render.render(write_still=True)
        report['rendered'] = render
print('VOLUME_REPORT ' + json.dumps(report))
