"""Cutaway for Blender: imports the glTF scenes and pieces cutaway writes, finishing what
Blender's glTF importer leaves undone, and cuts fruit with the cutaway executable from the Add
menu, and imports interior volumes. doc/blender.md in the cutaway sources describes them."""

bl_info = {
    "name": "Cutaway",
    "author": "The cutaway authors",
    "version": (0, 5, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > Cutaway Scene, Cutaway Volume; Add > Cut Fruit",
    "description": "Import cutaway's cut fruit scenes (camera, sky, translucent flesh, "
                   "levels of detail) and cut fruit with the cutaway executable",
    "category": "Import-Export",
}

import bpy  # noqa: E402

from . import operators, preferences  # noqa: E402

_classes = (preferences.CutawayPreferences,) + operators.classes


def register():
    """Registers the preferences, the operators and their menu entries."""
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.TOPBAR_MT_file_import.append(operators.menu_import)
    bpy.types.VIEW3D_MT_add.append(operators.menu_add)


def unregister():
    """Removes what register() added."""
    bpy.types.VIEW3D_MT_add.remove(operators.menu_add)
    bpy.types.TOPBAR_MT_file_import.remove(operators.menu_import)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
