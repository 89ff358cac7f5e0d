"""The imported objects: which glTF node each stands for, levels of detail and collision shapes
out of sight, the nodes' extras as custom properties, and one collection per cut object."""

import re

import bpy

from .gltf_file import is_collision_name

_DUPLICATE_SUFFIX = re.compile(r"\.\d{3,}$")
_PIECE_NAME = re.compile(r"^(.+)_piece\d+$")


def base_name(name):
    """A data-block's name without the .001 Blender appends to a name already taken."""
    return _DUPLICATE_SUFFIX.sub("", name)


def match_nodes(gltf, new_objects):
    """Maps glTF node indices to the objects Blender's importer made of them (by name; cutaway
    names every node, and uniquely)."""
    by_name = {}
    for index, node in enumerate(gltf.nodes):
        by_name.setdefault(node.get("name"), index)
    objects = {}
    for obj in new_objects:
        index = by_name.get(base_name(obj.name))
        if index is not None and index not in objects:
            objects[index] = obj
    return objects


def place_lods(gltf, objects):
    """Puts each coarser level of detail where its full level is (Blender's importer ignores
    MSFT_lod and leaves the levels, which no node lists as a child, at the top of the scene)
    and hides it in the viewport and in renders. Returns the level objects."""
    lods = []
    for lod_index, base_index in gltf.lod_nodes().items():
        lod, base = objects.get(lod_index), objects.get(base_index)
        if lod is None:
            continue
        if base is not None and lod.parent is None and base.parent is not None:
            lod.parent = base.parent  # the node's own transform is relative to that parent
        lod.hide_viewport = True
        lod.hide_render = True
        lods.append(lod)
    return lods


def hide_collision_shapes(new_objects):
    """Keeps collision shapes (UCX_*, *-colonly, *-convcolonly) out of renders and draws them
    as wires. Returns them."""
    shapes = [obj for obj in new_objects if is_collision_name(base_name(obj.name))]
    for obj in shapes:
        obj.hide_render = True
        obj.display_type = 'WIRE'
    return shapes


def copy_missing_extras(gltf, objects):
    """Sets each node's extras (template, seed, cut, piece, ...) as custom properties on its
    object where the importer has not already done so."""
    for index, obj in objects.items():
        extras = gltf.nodes[index].get("extras")
        if not isinstance(extras, dict):
            continue
        for key, value in extras.items():
            if key in obj.keys():
                continue
            try:
                obj[key] = value
            except (TypeError, ValueError, OverflowError):
                obj[key] = str(value)


def piece_objects(gltf, objects):
    """The objects of the nodes whose extras name a template and a seed: the cut pieces."""
    pieces = {}
    for index, obj in objects.items():
        extras = gltf.nodes[index].get("extras")
        if isinstance(extras, dict) and "template" in extras and "seed" in extras:
            pieces[obj] = (str(extras["template"]), str(extras["seed"]))
    return pieces


def collect(context, name, new_objects, pieces):
    """Moves the new objects into a collection called `name` (inside the active one) and the
    pieces of each cut object, with everything below them, into a child collection of it per
    template and seed. Returns the top collection."""
    top = bpy.data.collections.new(name)
    (context.collection or context.scene.collection).children.link(top)
    groups = {}
    for piece, key in pieces.items():
        groups.setdefault(key, []).append(piece)
    collection_of = {}
    for (template, seed), members in groups.items():
        group = bpy.data.collections.new(_group_name(template, seed, members, top.name))
        top.children.link(group)
        for piece in members:
            collection_of[piece] = group
    for obj in new_objects:
        owner = obj
        while owner is not None and owner not in collection_of:
            owner = owner.parent
        _move(obj, collection_of.get(owner, top))
    return top


def _group_name(template, seed, pieces, taken):
    """The name the pieces share before _pieceN (e.g. i2_kiwi_0), else 'TEMPLATE seed SEED'."""
    prefixes = {m.group(1) for m in (_PIECE_NAME.match(base_name(p.name)) for p in pieces) if m}
    if len(prefixes) == 1:
        prefix = prefixes.pop()
        if prefix != base_name(taken):
            return prefix
    return f"{template} seed {seed}"


def _move(obj, collection):
    for other in list(obj.users_collection):
        if other != collection:
            other.objects.unlink(obj)
    if collection not in obj.users_collection:
        collection.objects.link(obj)
