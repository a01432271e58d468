"""Caligo for Blender: File > Export > Caligo scene (.json), and Caligo as a render engine.

Install: Edit > Preferences > Add-ons > Install..., pick a zip of this folder (or copy the folder
into ~/.config/blender/3.4/scripts/addons/), enable "Render: Caligo", and set the path of the
`caligo` executable in the add-on's preferences (or put it on PATH, or set CALIGO_BINARY).
From a script: `from caligo_addon import export; export.export_scene(depsgraph, path)`.
"""
bl_info = {
    "name": "Caligo",
    "author": "The Caligo authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Export > Caligo scene; Render Properties > Render Engine",
    "description": "Export scenes to the Caligo volumetric path tracer and render with it",
    "category": "Render",
}

import os
import shutil
import signal
import subprocess
import tempfile
import time

import bpy
from bpy_extras.io_utils import ExportHelper

from . import export

ENGINE_ID = "CALIGO"


def caligo_binary(context=None):
    """The caligo executable: the add-on preference, CALIGO_BINARY, or PATH."""
    prefs = None
    try:
        prefs = (context or bpy.context).preferences.addons[__name__].preferences
    except (KeyError, AttributeError):
        pass
    for candidate in ((prefs.binary if prefs else ""), os.environ.get("CALIGO_BINARY", ""), shutil.which("caligo") or ""):
        if candidate and os.access(bpy.path.abspath(candidate), os.X_OK):
            return bpy.path.abspath(candidate)
    return None


def render_with_caligo(scene_path, exr_path, binary, spp=None, threads=None, should_stop=None, extra_args=()):
    """Runs `caligo render`; Ctrl-C-like stop when should_stop() turns true. Returns (exit code, stderr)."""
    args = [binary, "render", scene_path, "-o", exr_path, "-q", *extra_args]
    if spp:
        args += ["--spp", str(int(spp))]
    if threads:
        args += ["--threads", str(int(threads))]
    proc = subprocess.Popen(args, stderr=subprocess.PIPE, text=True)
    while proc.poll() is None:
        if should_stop is not None and should_stop():
            proc.send_signal(signal.SIGINT)  # caligo writes the partial image and stops
            break
        time.sleep(0.1)
    _, err = proc.communicate()
    return proc.returncode, err


class CaligoPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__
    binary: bpy.props.StringProperty(name="caligo executable", subtype='FILE_PATH', default="")

    def draw(self, context):
        self.layout.prop(self, "binary")


class CaligoSceneSettings(bpy.types.PropertyGroup):
    spp: bpy.props.IntProperty(name="Samples", default=64, min=1, max=1000000)


class CALIGO_OT_export(bpy.types.Operator, ExportHelper):
    """Export the scene as a Caligo scene file (meshes as PLY beside it)"""
    bl_idname = "export_scene.caligo"
    bl_label = "Export Caligo scene"
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        try:
            warnings = export.export_scene(context.evaluated_depsgraph_get(), self.filepath)
        except export.ExportError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        for w in warnings:
            self.report({'WARNING'}, w)
        return {'FINISHED'}


class CaligoRenderEngine(bpy.types.RenderEngine):
    bl_idname = ENGINE_ID
    bl_label = "Caligo"
    bl_use_preview = False

    def render(self, depsgraph):
        scene = depsgraph.scene
        binary = caligo_binary()
        if binary is None:
            self.report({'ERROR'}, "Caligo: no caligo executable (set it in the add-on's preferences)")
            return
        with tempfile.TemporaryDirectory(prefix="caligo-") as folder:
            path = os.path.join(folder, "scene.json")
            try:
                for w in export.export_scene(depsgraph, path, spp=scene.caligo.spp):
                    self.report({'WARNING'}, "Caligo: " + w)
            except export.ExportError as e:
                self.report({'ERROR'}, f"Caligo: {e}")
                return
            exr = os.path.join(folder, "beauty.exr")
            self.update_stats("Caligo", "rendering")
            # The beauty alone: Blender reads dotted channel names (N.X) as a multilayer file.
            code, err = render_with_caligo(path, exr, binary, should_stop=self.test_break, extra_args=("--aov", "beauty"))
            if not os.path.exists(exr):
                exr = os.path.join(folder, "beauty.partial.exr")
            if not os.path.exists(exr):
                self.report({'ERROR'}, f"Caligo failed (exit {code}): {err.strip()[-500:]}")
                return
            self.load_result(scene, exr)

    def load_result(self, scene, exr):
        image = bpy.data.images.load(exr, check_existing=False)
        try:
            w, h = image.size
            result = self.begin_result(0, 0, w, h)
            pixels = list(image.pixels)  # RGBA, rows bottom to top, as the render result wants
            result.layers[0].passes["Combined"].rect = [pixels[i:i + 4] for i in range(0, len(pixels), 4)]
            self.end_result(result)
        finally:
            bpy.data.images.remove(image)


def _menu_export(self, context):
    self.layout.operator(CALIGO_OT_export.bl_idname, text="Caligo scene (.json)")


def _compatible_panels():
    # Show the camera, light, world and output panels the Cycles/Eevee UI already has.
    for panel in bpy.types.Panel.__subclasses__():
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if engines is not None and 'BLENDER_RENDER' in engines:
            yield panel


_classes = (CaligoPreferences, CaligoSceneSettings, CALIGO_OT_export, CaligoRenderEngine)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.caligo = bpy.props.PointerProperty(type=CaligoSceneSettings)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.add(ENGINE_ID)


def unregister():
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.discard(ENGINE_ID)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    del bpy.types.Scene.caligo
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
