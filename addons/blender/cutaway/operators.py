"""The add-on's operators and their menu entries: File > Import > Cutaway Scene and Cutaway
Volume, and Add > Cut Fruit."""

import time

import bpy
from bpy.props import BoolProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from . import generator, importer, preferences, volume

_READ_ERRORS = (OSError, ValueError, RuntimeError)


class IMPORT_SCENE_OT_cutaway(bpy.types.Operator, ImportHelper):
    """Import a glTF file written by cutaway: its pieces, camera, lights and sky, with
    translucent cut faces and levels of detail hidden"""

    bl_idname = "import_scene.cutaway"
    bl_label = "Import Cutaway Scene"
    bl_options = {'REGISTER', 'UNDO', 'PRESET'}

    filename_ext = ".glb"
    filter_glob: StringProperty(default="*.glb;*.gltf", options={'HIDDEN'})
    use_camera: BoolProperty(
        name="Scene Camera",
        description="Make the file's camera, if it has one, the scene's camera and fit the "
                    "render's aspect ratio to it",
        default=True,
    )
    use_sky: BoolProperty(
        name="World Light",
        description="Light the world with the uniform sky the file expects (ambient_lux)",
        default=True,
    )
    use_exposure: BoolProperty(
        name="Exposure",
        description="Show the scene at the file's exposure under the Standard view",
        default=True,
    )

    def execute(self, context):
        try:
            imported = importer.import_file(context, self.filepath, use_camera=self.use_camera,
                                            use_sky=self.use_sky, use_exposure=self.use_exposure)
        except _READ_ERRORS as error:
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Imported {len(imported.pieces)} pieces into "
                              f"'{imported.collection.name}'")
        return {'FINISHED'}


class IMPORT_SCENE_OT_cutaway_volume(bpy.types.Operator, ImportHelper):
    """Import an interior volume written by cutaway volume (.vdb), standing where the object's
    glTF stands, with a material that shows the flesh's colour"""

    bl_idname = "import_scene.cutaway_volume"
    bl_label = "Import Cutaway Volume"
    bl_options = {'REGISTER', 'UNDO'}

    filename_ext = ".vdb"
    filter_glob: StringProperty(default="*.vdb", options={'HIDDEN'})

    def execute(self, context):
        try:
            obj = volume.import_volume(context, self.filepath)
        except _READ_ERRORS as error:
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Imported the interior volume '{obj.name}'")
        return {'FINISHED'}


def _search_templates(self, context, edit_text):
    """The template names the Template field suggests."""
    executable, folder = preferences.paths(context)
    if not folder:
        try:
            folder = generator.templates_dir("", generator.find_executable(executable))
        except generator.GeneratorError:
            return []
    return [name for name in generator.template_names(folder) if edit_text in name]


class OBJECT_OT_cutaway_add_cut_fruit(bpy.types.Operator):
    """Cut a fruit from a cutaway template and add its pieces at the 3D cursor (cutaway runs in
    the background; Esc cancels)"""

    bl_idname = "object.cutaway_add_cut_fruit"
    bl_label = "Cut Fruit"
    bl_options = {'REGISTER', 'UNDO'}

    template: StringProperty(
        name="Template",
        description="A template's name in the templates folder, or the path of a .yaml file",
        default="tomato",
        search=_search_templates,
    )
    cut: StringProperty(
        name="Cut",
        description="halves, slices:THICKNESS, wedges:COUNT, dice:SIZE, plane:SPEC or whole "
                    "(template units)",
        default="wedges:4",
    )
    seed: IntProperty(
        name="Seed",
        description="The random variant of the template to cut",
        default=1,
        min=0,
    )
    pulled_apart: BoolProperty(
        name="Pulled Apart",
        description="Place the pieces pulled slightly apart, as cutaway's preview shows them, "
                    "instead of assembled as cut",
        default=False,
    )

    _job = None
    _timer = None

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        """Starts the cut (a generator.CutJob). With a window, returns at once and the modal
        handler imports the pieces when cutaway is done (Esc cancels); in background mode
        (blender -b, scripts) it waits."""
        executable, folder = preferences.paths(context)
        try:
            executable = generator.find_executable(executable)
            template = generator.resolve_template(
                self.template, generator.templates_dir(folder, executable))
            self._job = generator.CutJob(executable, template, self.cut, self.seed,
                                         apart=0.3 if self.pulled_apart else 0.0)
        except _READ_ERRORS as error:
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        if bpy.app.background or context.window is None:
            try:
                while not self._job.poll():
                    time.sleep(0.05)
            except _READ_ERRORS as error:
                return self._end(context, error=str(error))
            return self._end(context)
        manager = context.window_manager
        self._timer = manager.event_timer_add(0.2, window=context.window)
        manager.modal_handler_add(self)
        self._show_progress(context)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        """Polls the cut on each timer tick; Esc stops it. Blender stays usable meanwhile."""
        if event.type == 'ESC':
            return self._end(context, error="cut cancelled", level='WARNING')
        if event.type != 'TIMER':
            return {'PASS_THROUGH'}
        try:
            if not self._job.poll():
                self._show_progress(context)
                return {'PASS_THROUGH'}
        except _READ_ERRORS as error:
            return self._end(context, error=str(error))
        return self._end(context)

    def _show_progress(self, context):
        if context.workspace is not None:
            context.workspace.status_text_set(
                f"Cutting {self.template} ({self.cut}): {self._job.seconds():.0f} s, "
                "Esc cancels")

    def _end(self, context, error=None, level='ERROR'):
        """Imports the pieces at the 3D cursor unless `error`; then stops the timer and the
        job and removes its folder."""
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        try:
            if error is not None:
                self.report({level}, error)
                return {'CANCELLED'}
            try:
                imported = importer.import_file(context, self._job.output)
            except _READ_ERRORS as failure:
                self.report({'ERROR'}, str(failure))
                return {'CANCELLED'}
            root = imported.root
            if root is None:
                self.report({'ERROR'}, "cutaway wrote a file without pieces")
                return {'CANCELLED'}
            root.location = context.scene.cursor.location
            for obj in context.selected_objects:
                obj.select_set(False)
            root.select_set(True)
            context.view_layer.objects.active = root
            return {'FINISHED'}
        finally:
            self._job.close()
            self._job = None


def menu_import(self, context):
    """File > Import entry."""
    self.layout.operator(IMPORT_SCENE_OT_cutaway.bl_idname, text="Cutaway Scene (.glb/.gltf)")
    self.layout.operator(IMPORT_SCENE_OT_cutaway_volume.bl_idname, text="Cutaway Volume (.vdb)")


def menu_add(self, context):
    """Add menu entry."""
    self.layout.operator(OBJECT_OT_cutaway_add_cut_fruit.bl_idname, text="Cut Fruit",
                         icon='MESH_UVSPHERE')


classes = (IMPORT_SCENE_OT_cutaway, IMPORT_SCENE_OT_cutaway_volume,
           OBJECT_OT_cutaway_add_cut_fruit)
