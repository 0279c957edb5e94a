"""knit_blender: drape a knit (libknit) on the active mesh as ply curves, animated with the mesh.

Object > Knit > Apply Knit (bpy.ops.object.knit_apply) binds the pattern to the active mesh once
and creates `<mesh>.knit`: a mesh of edges (one chain per ply) with a `radius` point attribute and
a geometry-nodes modifier (Mesh to Curve -> Set Curve Radius -> Curve to Mesh with a circle
profile) that Cycles and EEVEE render as tubes. On every frame change the evaluated source mesh
(modifiers, shape keys) is read and the plies are re-evaluated through the Python module `knit`
(Scene.evaluate_plies: the Animator of `knit animate`, so frame k equals its frame k).
Object > Knit > Bake Knit to PC2 (bpy.ops.object.knit_bake_pc2) writes the frames to a PC2 cache.

Nothing prints a traceback. A knit whose source no longer matches its binding (the vertex or face
count changed by a modifier such as Decimate or Remesh, the source deleted, its UV map changed,
the module knit missing) keeps its last good shape and says why once: a line on the console and
the status bar, and in the Knit panel of the object's properties for as long as it lasts, with
Re-apply Knit (bpy.ops.object.knit_reapply: binds again, with the same options, to the source as
it is now). A renamed source (the knit's parent) or UV map (the same coordinates) is followed.
Errors name the operator's properties (Repeats, Plies, Ply pitch), never a command line flag or a
Python keyword.

The module `knit` is found on sys.path (installed into Debian's dist-packages by `cmake --install`),
else in the folders of the environment variable KNIT_PYTHONPATH or of the add-on preference
"Module folder" (e.g. <checkout>/build/python).
"""
bl_info = {
    "name": "Knit (libknit)",
    "author": "libknit",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Object > Knit",
    "description": "Ply-level knitted fabric on the active mesh, animated with it",
    "category": "Object",
}

import importlib

if "bpy" in locals():
    importlib.reload(build)  # noqa: F821 (Blender's add-on reload)
import bpy

from . import build
from .build import ADDON, knit_module, missing_module_message


class KnitPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON
    module_folder: bpy.props.StringProperty(
        name="Module folder", subtype="DIR_PATH",
        description="Folder holding the knit package (e.g. <checkout>/build/python), if not installed")


def report_warnings(operator, warnings):
    """The chart's warnings (build.chart_warnings), each a WARNING report: the status bar and the
    Info editor show them, as `knit chart` prints them."""
    for text in warnings:
        operator.report({"WARNING"}, text)


class OBJECT_OT_knit_apply(bpy.types.Operator):
    """Bind a knit pattern to the active mesh and create <mesh>.knit (ply curves)"""
    bl_idname = "object.knit_apply"
    bl_label = "Apply Knit"
    bl_options = {"REGISTER", "UNDO"}

    pattern: bpy.props.StringProperty(name="Pattern", default="stockinette",
                                      description="Built-in pattern name (or chart:NAME), or a .pyp / .json / "
                                                  ".chart file")
    chart_text: bpy.props.StringProperty(name="Chart text", default="",
                                         description="A text block holding a stitch chart (libknit docs/charts.md); "
                                                     "when set it replaces Pattern")
    repeats: bpy.props.FloatVectorProperty(name="Repeats", size=2, default=(8.0, 8.0), min=0.0,
                                           description="Pattern periods across the UV square (0, 0: see Gauge)")
    gauge: bpy.props.FloatVectorProperty(name="Gauge", size=2, default=(0.0, 0.0), min=0.0,
                                         description="Pattern periods per 10 cm along u and v; overrides Repeats when set")
    plies: bpy.props.IntProperty(name="Plies", default=2, min=1, max=16)
    ply_pitch: bpy.props.FloatProperty(name="Ply pitch", default=0.0, min=0.0, unit="LENGTH",
                                       description="Length of one ply turn; 0 = 6 yarn radii")
    twist: bpy.props.EnumProperty(name="Twist", items=[("S", "S", "S twist"), ("Z", "Z", "Z twist")], default="S")
    profile_resolution: bpy.props.IntProperty(name="Profile sides", default=6, min=3, max=32)
    deform: bpy.props.EnumProperty(
        name="Deform", default="auto",
        items=[("auto", "Automatic", "Strain-aware where the pattern's strain table is cached or made in seconds, "
                                     "else geometric (libknit's default; docs/deformation.md)"),
               ("none", "Geometric", "Yarns follow the surface as drawn on it (they stretch where it stretches)"),
               ("strain", "Strain-aware", "Yarns slide and bend as the pattern's strain table says (made on first "
                                          "use and cached; libknit docs/deformation.md)")],
        description="How the yarns follow a stretched, sheared or compressed surface")

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def execute(self, context):
        try:
            knit_module()
        except ImportError as e:
            self.report({"ERROR"}, missing_module_message(e))
            return {"CANCELLED"}
        why = self.refusal()
        if why:
            self.report({"ERROR"}, why)
            return {"CANCELLED"}
        options = self.as_keywords()
        if self.chart_text:  # the chart's text is stored with the object, so a re-bind uses it
            options["chart_source"] = bpy.data.texts[self.chart_text].as_string()
        try:
            obj = build.apply_knit(context, context.active_object, options)
            said = build.chart_warnings(options)
        except Exception as e:  # noqa: BLE001 - reported in the interface, never a traceback
            self.report({"ERROR"}, build.message_of(e))
            return {"CANCELLED"}
        report_warnings(self, said)
        self.report({"INFO"}, f"{obj.name}: {len(obj.data.vertices)} ply points")
        return {"FINISHED"}


    def refusal(self):
        """Why the properties cannot be applied together, or "" (the library checks each value)."""
        for name, pair in (("Repeats", self.repeats), ("Gauge", self.gauge)):
            if (pair[0] > 0) != (pair[1] > 0):
                return (f"{name} ({pair[0]:g}, {pair[1]:g}): set both (along u and v) or neither (0, 0), "
                        "not one")
        if self.chart_text:
            block = bpy.data.texts.get(self.chart_text)
            if block is None:
                return f"Chart text: there is no text block named '{self.chart_text}'"
            if not block.as_string().strip():
                return f"Chart text: the text block '{self.chart_text}' is empty (write a stitch chart in it)"
        return ""


class OBJECT_OT_knit_reapply(bpy.types.Operator):
    """Bind the active knit object again, with the options it was applied with, to its source as it is now"""
    bl_idname = "object.knit_reapply"
    bl_label = "Re-apply Knit"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and build.SOURCE_PROP in obj

    def execute(self, context):
        obj = context.active_object
        try:
            build.knit_module()
        except ImportError as e:
            self.report({"ERROR"}, missing_module_message(e))
            return {"CANCELLED"}
        source = build.source_of(obj)
        if source is None:
            self.report({"ERROR"}, f"{obj.name}: its source mesh '{obj[build.SOURCE_PROP]}' no longer exists; "
                                   "select a mesh and use Apply Knit")
            return {"CANCELLED"}
        try:
            options = build.options_of(obj)
            new = build.apply_knit(context, source, options)
            said = build.chart_warnings(options)
        except Exception as e:  # noqa: BLE001 - reported in the interface, never a traceback
            self.report({"ERROR"}, build.message_of(e))
            return {"CANCELLED"}
        report_warnings(self, said)
        context.view_layer.objects.active = new
        self.report({"INFO"}, f"{new.name}: re-applied, {len(new.data.vertices)} ply points")
        return {"FINISHED"}


class OBJECT_OT_knit_bake_pc2(bpy.types.Operator):
    """Write the active knit object's points for a frame range to a PC2 point cache"""
    bl_idname = "object.knit_bake_pc2"
    bl_label = "Bake Knit to PC2"

    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    frame_start: bpy.props.IntProperty(name="Start", default=1)
    frame_end: bpy.props.IntProperty(name="End", default=250)

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and build.SOURCE_PROP in obj

    def execute(self, context):
        path = self.filepath or f"//{context.active_object.name}.pc2"
        if path.startswith("//") and not bpy.data.filepath:  # relative to a .blend file not saved yet
            self.report({"ERROR"}, f"File path: '{path}' is relative to the .blend file, which is not saved yet; "
                                   "save the .blend file or choose a full path; nothing written")
            return {"CANCELLED"}
        path = bpy.path.abspath(path)
        if not path.lower().endswith(".pc2"):  # another file (a .blend, a pattern) would be overwritten
            self.report({"ERROR"}, f"File path: '{path}' is not a .pc2 name (a PC2 point cache is written there); "
                                   "nothing written")
            return {"CANCELLED"}
        if self.frame_end < self.frame_start:
            self.report({"ERROR"}, f"End ({self.frame_end}) is before Start ({self.frame_start}); nothing written")
            return {"CANCELLED"}
        for name, frame in (("Start", self.frame_start), ("End", self.frame_end)):
            if abs(frame) > MAX_FRAME:
                self.report({"ERROR"}, f"{name} ({frame}) is beyond Blender's frames (-{MAX_FRAME} to {MAX_FRAME}); "
                                       "nothing written")
                return {"CANCELLED"}
        try:
            frames = build.bake_pc2(context, context.active_object, path, self.frame_start, self.frame_end)
        except Exception as e:  # noqa: BLE001 - reported in the interface, never a traceback
            self.report({"ERROR"}, f"{path}: {build.message_of(e)}; nothing written")
            return {"CANCELLED"}
        self.report({"INFO"}, f"{path}: {frames} frames")
        return {"FINISHED"}


MAX_FRAME = 1048574  # Blender's last frame (MAXFRAME): scene.frame_set clamps beyond it


class OBJECT_PT_knit(bpy.types.Panel):
    """Object properties > Knit: whether the knit follows its source, and Re-apply."""
    bl_label = "Knit"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and build.SOURCE_PROP in obj

    def draw(self, context):
        obj = context.active_object
        status = obj.get(build.STATUS_PROP, "")
        self.layout.label(text=f"Source: {obj[build.SOURCE_PROP]}")
        if status:
            box = self.layout.box()
            for k, line in enumerate(_wrapped(status, 60)):
                box.label(text=line, icon="ERROR" if k == 0 else "BLANK1")
        self.layout.operator(OBJECT_OT_knit_reapply.bl_idname, icon="FILE_REFRESH")


def _wrapped(text, width):
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    return lines + ([line] if line else [])


class VIEW3D_MT_knit(bpy.types.Menu):
    bl_label = "Knit"

    def draw(self, context):
        self.layout.operator(OBJECT_OT_knit_apply.bl_idname)
        self.layout.operator(OBJECT_OT_knit_reapply.bl_idname)
        self.layout.operator(OBJECT_OT_knit_bake_pc2.bl_idname)


def _menu(self, context):
    self.layout.menu("VIEW3D_MT_knit")


_classes = (KnitPreferences, OBJECT_OT_knit_apply, OBJECT_OT_knit_reapply, OBJECT_OT_knit_bake_pc2, OBJECT_PT_knit,
            VIEW3D_MT_knit)


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.VIEW3D_MT_object.append(_menu)
    if build.on_frame_change not in bpy.app.handlers.frame_change_post:
        bpy.app.handlers.frame_change_post.append(build.on_frame_change)
    if build.on_load not in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.append(build.on_load)


def unregister():
    if build.on_frame_change in bpy.app.handlers.frame_change_post:
        bpy.app.handlers.frame_change_post.remove(build.on_frame_change)
    if build.on_load in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(build.on_load)
    bpy.types.VIEW3D_MT_object.remove(_menu)
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
