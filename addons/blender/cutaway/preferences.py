"""The add-on's preferences: where the cutaway executable and the templates are."""

import bpy
from bpy.props import StringProperty


class CutawayPreferences(bpy.types.AddonPreferences):
    """Paths the Add > Cut Fruit operator needs."""

    bl_idname = __package__

    executable: StringProperty(
        name="cutaway Executable",
        description="The cutaway program (a path, or a name found on PATH)",
        subtype='FILE_PATH',
        default="cutaway",
    )
    templates_dir: StringProperty(
        name="Templates Folder",
        description="Folder of template .yaml files; empty: templates/ beside the folder that "
                    "holds the executable",
        subtype='DIR_PATH',
        default="",
    )

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "executable")
        layout.prop(self, "templates_dir")


def paths(context):
    """The executable and templates folder settings, Blender's '//' relative paths made
    absolute."""
    prefs = context.preferences.addons[__package__].preferences
    return bpy.path.abspath(prefs.executable), bpy.path.abspath(prefs.templates_dir)
