"""The add-on's steps: read the source mesh, bind (knit.build_scene), write the ply mesh, build
the geometry-nodes modifier, re-evaluate on frame change, bake PC2.

Every pose, the bind pose included, is evaluated by Scene.evaluate_plies: the library's Animator,
the one `knit animate` runs, so frame k here is frame k of `knit animate` on the same meshes and
options (the point layout, twist phase and ply frames are fixed at bind time)."""
import itertools
import json
import os
import re
import struct
import sys
import warnings
import zlib

import bpy
import numpy as np

ADDON = __package__ or "knit_blender"
SOURCE_PROP = "knit_source"    # on <mesh>.knit: the source object's name
OPTIONS_PROP = "knit_options"  # on <mesh>.knit: the apply options (JSON), to re-bind after a reload
REST_PROP = "knit_rest"        # on <mesh>.knit: the bind pose's vertex positions (float array), ditto
BOUND_PROP = "knit_bound"      # on <mesh>.knit: what the binding needs of its source (JSON, signature_of)
STATUS_PROP = "knit_status"    # on <mesh>.knit: why it no longer follows its source ("" = it does)
NODE_GROUP = "knit_ply_curves"
MATERIAL = "knit_yarn"

# Bound scenes by knit object name. Blender cannot store Python objects in a .blend file, so a
# scene missing here (after loading a file) is re-bound from OPTIONS_PROP and REST_PROP on first
# use: the same options on the same pose, so the same scene, whichever frame the file opens on.
_scenes = {}


def knit_module():
    """The Python module knit: from sys.path, else KNIT_PYTHONPATH or the add-on preference."""
    try:
        import knit
        return knit
    except ImportError:
        pass
    folders = os.environ.get("KNIT_PYTHONPATH", "").split(os.pathsep)
    addon = bpy.context.preferences.addons.get(ADDON)
    if addon and addon.preferences and addon.preferences.module_folder:
        folders.append(bpy.path.abspath(addon.preferences.module_folder))
    for f in filter(None, folders):
        if f not in sys.path:
            sys.path.append(f)
    import knit
    return knit


def missing_module_message(error):
    """Why the module knit could not be imported, and where Blender looks for it (every operator
    and the frame handler say it in these words)."""
    return (f"the Python module knit was not found ({error}): install libknit's Python module, or set the "
            "add-on's Module folder (Edit > Preferences > Add-ons > Knit) or the environment variable "
            "KNIT_PYTHONPATH to <libknit build>/python")


def source_of(obj):
    """The source mesh object of a knit object: the one named in SOURCE_PROP, else (renamed) the
    mesh it is parented to, whose new name is then recorded; None when it was deleted."""
    source = bpy.data.objects.get(obj[SOURCE_PROP])
    if source is None and obj.parent is not None and obj.parent.type == "MESH":
        source = obj.parent
        try:
            obj[SOURCE_PROP] = source.name
        except (AttributeError, RuntimeError, TypeError):  # ID writes not allowed here (rendering)
            pass
    return source if source is not None and source.type == "MESH" else None


def options_of(obj):
    """The apply options stored on a knit object (OPTIONS_PROP); ValueError when damaged."""
    try:
        options = json.loads(obj[OPTIONS_PROP])
        if not isinstance(options, dict):
            raise ValueError("not a JSON object")
        return options
    except (ValueError, TypeError, KeyError) as e:
        raise ValueError(f"{obj.name}: its stored apply options (custom property {OPTIONS_PROP}) are damaged "
                         f"({e}); select its source and use Apply Knit") from None


# -- Step 1: the source mesh as arrays ------------------------------------------------------------

def read_frame(obj, depsgraph):
    """(positions, signature) of the evaluated object (modifiers, shape keys), local space:
    vertex positions (n, 3) float32, and what the binding depends on (signature_of)."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
        return co.reshape(-1, 3), signature_of(mesh)
    finally:
        evaluated.to_mesh_clear()


def read_positions(obj, depsgraph):
    """Vertex positions (n, 3) float32 of the evaluated object (modifiers, shape keys), local space."""
    return read_frame(obj, depsgraph)[0]


def signature_of(mesh):
    """What a binding depends on besides the positions: the vertex and face counts, the active UV
    map's name and a checksum of its coordinates. A change of any of them (Decimate, Remesh, an
    edited or another UV map) makes the bound knit invalid for the mesh."""
    uv = mesh.uv_layers.active
    crc = None
    if uv is not None:
        uvs = np.empty(len(mesh.loops) * 2, dtype=np.float32)
        uv.data.foreach_get("uv", uvs)
        crc = zlib.crc32(uvs.tobytes())
    return {"vertices": len(mesh.vertices), "faces": len(mesh.polygons), "uv_map": uv.name if uv else None,
            "uv_crc": crc}


def signature_change(bound, now):
    """Why the source no longer matches its binding (in the interface's words), or ""."""
    if bound["vertices"] != now["vertices"]:
        return (f"the source now has {now['vertices']} vertices, the knit was bound to {bound['vertices']} "
                "(a modifier such as Decimate or Remesh, or an edit, changed them)")
    if bound["faces"] != now["faces"]:
        return f"the source now has {now['faces']} faces, the knit was bound to {bound['faces']}"
    if bound["uv_crc"] == now["uv_crc"]:  # the same coordinates (a renamed UV map is the same map)
        return ""
    if bound["uv_map"] != now["uv_map"]:
        return (f"the source's active UV map is now {now['uv_map'] or 'none'!s}, "
                f"the knit was bound to {bound['uv_map']}")
    return f"the source's UV map {now['uv_map']} changed since the knit was bound"


def weld_corner_uvs(faces, corner_uvs):
    """(uvs, face_uvs) with one UV vertex per distinct (vertex, uv) pair, numbered in first-use
    order over the triangle corners: what knit's mesh loaders make of an OBJ, so a UV seam is
    only where the UVs differ (one UV per loop would make every triangle edge a seam, cutting the
    yarns there). faces (m, 3) vertex indices; corner_uvs (m, 3, 2) the UV of each corner."""
    uv = np.asarray(corner_uvs, dtype=np.float64).reshape(-1, 2) + 0.0  # -0 -> +0, as the loaders
    keys = np.empty(len(uv), dtype=[("vertex", np.int64), ("u", np.float64), ("v", np.float64)])
    keys["vertex"], keys["u"], keys["v"] = np.asarray(faces).reshape(-1), uv[:, 0], uv[:, 1]
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    order = np.argsort(first)  # the distinct pairs in first-use order
    rank = np.empty(len(order), dtype=np.int64)
    rank[order] = np.arange(len(order))
    return uv[first[order]], rank[inverse.reshape(-1)].reshape(-1, 3)


def read_mesh(obj, depsgraph, positions=None):
    """knit.Mesh of the evaluated object: triangles, positions (or `positions`, (n, 3) float32, for
    the same vertices), the active UV map (welded per vertex as the mesh loaders weld an OBJ's,
    weld_corner_uvs). Vertices are kept as they are (one per Blender vertex: the frames'
    positions map onto them one to one)."""
    knit = knit_module()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        if not mesh.uv_layers.active:
            raise ValueError(f"{obj.name}: the mesh has no UV map (knit tiles the pattern in UV space)")
        mesh.calc_loop_triangles()
        tris = len(mesh.loop_triangles)
        co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
        if positions is not None and positions.size == co.size:
            co = positions
        faces = np.empty(tris * 3, dtype=np.int64)
        mesh.loop_triangles.foreach_get("vertices", faces)
        loops = np.empty(tris * 3, dtype=np.int64)
        mesh.loop_triangles.foreach_get("loops", loops)
        uvs = np.empty(len(mesh.loops) * 2, dtype=np.float32)
        mesh.uv_layers.active.data.foreach_get("uv", uvs)
        faces = faces.reshape(-1, 3)
        welded, face_uvs = weld_corner_uvs(faces, uvs.reshape(-1, 2)[loops.reshape(-1, 3)])
        return knit.Mesh(co.reshape(-1, 3), faces, welded, face_uvs, obj.name)
    finally:
        evaluated.to_mesh_clear()


# -- Step 2: bind ---------------------------------------------------------------------------------

def pattern_path(options):
    """The operator's Pattern: a name, or a file with Blender's '//' (relative to the .blend file) resolved."""
    pattern = options["pattern"]
    return bpy.path.abspath(pattern) if pattern.startswith("//") else pattern


def chart_name(options):
    """The name a Chart text block's chart is given (its errors and warnings name it)."""
    return options.get("chart_text") or "chart text"


def chart_warnings(options):
    """The chart's warnings in the library's words (knit.chart_warnings: a float longer than 5
    stitches, an intarsia repeat knitted taller than drawn), for Apply Knit and Re-apply to
    report: the Chart text block's chart, or a chart Pattern (chart:NAME, .chart); [] otherwise.
    Without the Python keyword "(max_float)": the add-on has no such setting."""
    knit = knit_module()
    if options.get("chart_source"):
        return knit.chart_warnings(options["chart_source"], name=chart_name(options), keywords=False)
    text = knit.chart_text(pattern_path(options))
    return [] if text is None else knit.chart_warnings(text, name=pattern_path(options), keywords=False)


def bind(source, options, depsgraph, rest=None):
    """knit.build_scene on the source's evaluated mesh (its positions replaced by `rest`, the bind
    pose, when given) with the operator's options (no plies: every pose's plies, the bind pose's
    too, come from Scene.evaluate_plies)."""
    knit = knit_module()
    mesh = read_mesh(source, depsgraph, rest)
    repeats = tuple(options["repeats"])
    gauge = tuple(options.get("gauge", (0.0, 0.0)))
    if gauge[0] > 0 and gauge[1] > 0:  # periods per 10 cm -> periods across the UV square
        su, sv = knit.uv_to_metre_scale(mesh)
        repeats = (su * gauge[0] / 0.1, sv * gauge[1] / 0.1)
    pattern = pattern_path(options)
    if options.get("chart_source"):  # chart text from a text block (the operator's Chart text)
        with warnings.catch_warnings():  # Apply Knit reports them (chart_warnings), once
            warnings.simplefilter("ignore", knit.ChartWarning)
            pattern = knit.chart_pattern(options["chart_source"], name=chart_name(options))
    deform = options.get("deform", "auto")
    if deform == "strain":
        require_quick_strain_table(knit, pattern)
    try:
        with warnings.catch_warnings():  # a chart file or chart:NAME warns too: Apply Knit reports it, once
            warnings.simplefilter("ignore", knit.ChartWarning)
            return knit.build_scene(pattern, mesh, repeats=repeats if repeats[0] > 0 else None,
                                    plies=options["plies"], ply_pitch=options["ply_pitch"], twist=options["twist"],
                                    deform={"auto": ""}.get(deform, deform),
                                    build_plies=False)
    except knit.Error as e:
        if not (gauge[0] > 0 and gauge[1] > 0) or getattr(e, "words", None) is None:
            raise
        # The repeats came from Gauge, not from the Repeats the user left alone.
        names = [("the repeats", "from Gauge")] + [n for n in PROPERTY_NAMES if n[0] != "the repeats"]
        raise ValueError(knit.spell_settings(e.words, names)) from None


# Blender does not respond while an operator runs: Strain-aware makes a pattern's missing strain
# table only when that takes about this long at most (Automatic's rule, strainTableIsQuick, or the
# estimate).
MAX_TABLE_SECONDS = 60.0


def require_quick_strain_table(knit, pattern):
    """Deform Strain-aware on a pattern whose strain table is neither cached nor quick to make:
    refused (ValueError) with the estimate, rather than Blender not responding for minutes."""
    at_hand = knit.strain_table_at_hand(pattern)
    if at_hand["quick"] or at_hand["seconds"] <= MAX_TABLE_SECONDS:
        return
    minutes = at_hand["seconds"] / 60.0
    raise ValueError(f"Deform Strain-aware: the pattern's strain table is not made yet, and making it would take "
                     f"about {minutes:.0f} minutes with Blender not responding; choose Deform Automatic or "
                     "Geometric, or make the table once outside Blender (libknit docs/deformation.md: it is "
                     "cached, and Strain-aware then uses it)")


# -- Step 3: the ply mesh (edges + radius) --------------------------------------------------------

def curve_edges(offsets, closed):
    """(k, 2) edges chaining each curve's points, closed curves back to their first point."""
    offsets = np.asarray(offsets, dtype=np.int64)
    n = int(offsets[-1])
    starts, ends = offsets[:-1], offsets[1:]
    inner = np.ones(max(n - 1, 0), dtype=bool)
    inner[(ends[ends < n]) - 1] = False  # no edge from a curve's last point to the next curve
    a = np.nonzero(inner)[0]
    edges = np.stack([a, a + 1], axis=1)
    loop = np.nonzero((np.asarray(closed) != 0) & (ends - starts > 2))[0]
    closing = np.stack([ends[loop] - 1, starts[loop]], axis=1)
    return np.concatenate([edges, closing]).astype(np.int32)


def fill_ply_mesh(mesh, plies, radius):
    """Replaces the mesh's geometry with the ply points, their edges and a `radius` point attribute."""
    mesh.clear_geometry()
    n = plies.point_count
    edges = curve_edges(plies.offsets, plies.closed)
    mesh.vertices.add(n)
    mesh.vertices.foreach_set("co", plies.points.astype(np.float32).ravel())
    mesh.edges.add(len(edges))
    mesh.edges.foreach_set("vertices", edges.ravel())
    attr = mesh.attributes.get("radius") or mesh.attributes.new("radius", "FLOAT", "POINT")
    attr.data.foreach_set("value", np.full(n, radius, dtype=np.float32))
    mesh.update()


def set_ply_points(mesh, plies):
    """Moves the mesh's vertices to the plies (same layout); returns False when the count differs."""
    if len(mesh.vertices) != plies.point_count:
        return False
    mesh.vertices.foreach_set("co", plies.points.astype(np.float32).ravel())
    mesh.update()
    return True


# -- Step 4: geometry nodes: Mesh to Curve -> Set Curve Radius -> Curve to Mesh (circle) ----------

def _output(node, type_):
    return next(s for s in node.outputs if s.type == type_ and s.enabled)


def ply_node_group(profile_resolution):
    group = bpy.data.node_groups.new(NODE_GROUP, "GeometryNodeTree")
    group.inputs.new("NodeSocketGeometry", "Geometry")
    group.outputs.new("NodeSocketGeometry", "Geometry")
    nodes, links = group.nodes, group.links
    source, sink = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    to_curve = nodes.new("GeometryNodeMeshToCurve")
    radius = nodes.new("GeometryNodeInputNamedAttribute")
    radius.data_type = "FLOAT"
    radius.inputs["Name"].default_value = "radius"
    set_radius = nodes.new("GeometryNodeSetCurveRadius")
    circle = nodes.new("GeometryNodeCurvePrimitiveCircle")
    circle.mode = "RADIUS"
    circle.inputs["Resolution"].default_value = profile_resolution
    circle.inputs["Radius"].default_value = 1.0  # scaled by each point's curve radius
    to_mesh = nodes.new("GeometryNodeCurveToMesh")
    material = nodes.new("GeometryNodeSetMaterial")
    material.inputs["Material"].default_value = yarn_material()
    links.new(source.outputs["Geometry"], to_curve.inputs["Mesh"])
    links.new(to_curve.outputs["Curve"], set_radius.inputs["Curve"])
    links.new(_output(radius, "VALUE"), set_radius.inputs["Radius"])
    links.new(set_radius.outputs["Curve"], to_mesh.inputs["Curve"])
    links.new(circle.outputs["Curve"], to_mesh.inputs["Profile Curve"])
    links.new(to_mesh.outputs["Mesh"], material.inputs["Geometry"])
    links.new(material.outputs["Geometry"], sink.inputs["Geometry"])
    return group


def yarn_material():
    material = bpy.data.materials.get(MATERIAL)
    if material is None:
        material = bpy.data.materials.new(MATERIAL)
        material.use_nodes = True
        bsdf = material.node_tree.nodes.get("Principled BSDF")
        if bsdf:
            bsdf.inputs["Base Color"].default_value = (0.8, 0.25, 0.2, 1.0)
            bsdf.inputs["Roughness"].default_value = 0.7
    return material


# -- The operator's pipeline ----------------------------------------------------------------------

def apply_knit(context, source, options):
    """Bind, then create (or replace) <mesh>.knit parented to the source; returns it."""
    depsgraph = context.evaluated_depsgraph_get()
    options = {k: (list(v) if hasattr(v, "__len__") and not isinstance(v, str) else v) for k, v in options.items()}
    scene = bind(source, options, depsgraph)
    plies = scene.evaluate_plies(scene.mesh.positions)  # may fail: before the previous knit is replaced
    signature = read_frame(source, depsgraph)[1]
    name = f"{source.name}.knit"
    old = bpy.data.objects.get(name)
    if old is not None:
        bpy.data.objects.remove(old)
    mesh = bpy.data.meshes.new(name)
    fill_ply_mesh(mesh, plies, scene.ply_radius)
    obj = bpy.data.objects.new(name, mesh)
    context.collection.objects.link(obj)
    obj.parent = source  # follows the source's transform; points are in its local space
    obj[SOURCE_PROP] = source.name
    obj[OPTIONS_PROP] = json.dumps(options)
    obj[REST_PROP] = np.asarray(scene.mesh.positions, dtype=np.float32).ravel().tolist()
    obj[BOUND_PROP] = json.dumps(signature)
    obj[STATUS_PROP] = ""
    _said[obj.name] = ""
    modifier = obj.modifiers.new("knit plies", "NODES")
    modifier.node_group = ply_node_group(options.get("profile_resolution", 6))
    _scenes[obj.name] = scene
    return obj


def scene_of(obj, depsgraph):
    """The bound knit.Scene of a knit object, re-bound from its stored options and bind pose if
    needed (an object applied before the pose was stored binds the source's current mesh)."""
    scene = _scenes.get(obj.name)
    if scene is None:
        source = source_of(obj)
        rest = obj.get(REST_PROP)
        rest = None if rest is None else np.array(rest, dtype=np.float32).reshape(-1, 3)
        scene = _scenes[obj.name] = bind(source, options_of(obj), depsgraph, rest)
    return scene


# -- Frame changes: follow the source, or say once why not ------------------------------------------

# The interface's names of the settings library messages name (knit.Error.words): the operator's
# properties; settings it has no property for stay in words.
PROPERTY_NAMES = [
    ("the repeats", "Repeats"),
    ("the gauge", "Gauge"),
    ("the number of plies", "Plies"),
    ("the ply pitch", "Ply pitch"),
    ("the twist direction", "Twist"),
    ("the deform mode", "Deform"),
]
REAPPLY_HINT = "Object > Knit > Re-apply Knit binds it to the source as it is now"

# The module's array arguments as the add-on fills them: a row of positions is a vertex of the
# source (one to one), a UV row one of its active UV map's (welded, so no loop index).
ARRAY_NAMES = [(re.compile(r"\bpositions: row (\d+)"), r"the source's vertex \1"),
               (re.compile(r"\b(face_)?uvs: row \d+"), "a UV of the source's active UV map")]


def message_of(error):
    """An exception as the interface shows it: a knit.Error in the operator's property names,
    anything else as its type and message (no traceback)."""
    words = getattr(error, "words", None)
    if words is not None:
        try:
            text = knit_module().spell_settings(words, PROPERTY_NAMES)
        except ImportError:
            text = words
    elif isinstance(error, (ValueError, OSError)):
        text = str(error)
    else:
        text = f"{type(error).__name__}: {error}"
    for pattern, name in ARRAY_NAMES:
        text = pattern.sub(name, text)
    return text


def follow_source(obj, depsgraph):
    """Re-evaluates one knit object on its source's current evaluated mesh (Scene.evaluate_plies:
    the same point count on every frame); returns "" or why it cannot (its points then stay as
    they were: the last good shape)."""
    try:
        knit_module()
    except ImportError as e:
        return missing_module_message(e)
    source = source_of(obj)
    if source is None:
        return (f"its source mesh '{obj[SOURCE_PROP]}' was deleted; it keeps its last shape. Select a mesh and "
                "use Object > Knit > Apply Knit (Re-apply Knit needs its source)")
    positions, signature = read_frame(source, depsgraph)
    bound = obj.get(BOUND_PROP)
    change = signature_change(json.loads(bound), signature) if bound else ""
    if change:
        return f"{change}; it keeps its last shape. {REAPPLY_HINT}"
    scene = scene_of(obj, depsgraph)
    if len(positions) != len(scene.mesh.positions):  # a knit applied before the signature was stored
        return (f"the source now has {len(positions)} vertices, the knit was bound to "
                f"{len(scene.mesh.positions)}; it keeps its last shape. {REAPPLY_HINT}")
    plies = scene.evaluate_plies(positions)
    if not set_ply_points(obj.data, plies):
        fill_ply_mesh(obj.data, plies, scene.ply_radius)
    return ""


def update_knit(obj, depsgraph):
    """follow_source, never raising: an error becomes the object's status."""
    try:
        status = follow_source(obj, depsgraph)
    except Exception as e:  # noqa: BLE001 - a handler must not raise: the status says what happened
        status = f"{message_of(e)}; it keeps its last shape. {REAPPLY_HINT}"
    set_status(obj, status)
    return status


# What was last said per knit object (by name): said once even where the object cannot be written
# (Blender refuses ID writes in some contexts, e.g. while rendering an animation).
_said = {}


def set_status(obj, status):
    """Records why the knit object no longer follows its source ("" = it does) and says so once:
    one line on the console and the status bar when it changes, the object's panel while it lasts."""
    if _said.get(obj.name, obj.get(STATUS_PROP, "")) == status:
        return
    _said[obj.name] = status
    try:
        obj[STATUS_PROP] = status
    except (AttributeError, RuntimeError, TypeError):  # ID writes not allowed here: the console says it
        pass
    text = f"{obj.name}: {status}" if status else None
    if text:
        print(f"knit: warning: {text}")
    try:
        for window in bpy.context.window_manager.windows:
            window.workspace.status_text_set(text)
    except (AttributeError, RuntimeError):  # no windows in background mode
        pass


@bpy.app.handlers.persistent
def on_load(*_):
    """Another .blend file was opened: the bound scenes and statuses of this session's knit objects
    belong to the old one (a knit of the same name there may be bound otherwise)."""
    _scenes.clear()
    _said.clear()


@bpy.app.handlers.persistent
def on_frame_change(scene, depsgraph=None):
    """Every knit object follows its source; one that cannot keeps its shape and says why (update_knit)."""
    try:
        depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
        objects = [obj for obj in scene.objects if SOURCE_PROP in obj and obj.type == "MESH"]
    except Exception as e:  # noqa: BLE001 - a handler must not raise
        print(f"knit: warning: the frame change could not be followed: {message_of(e)}")
        return
    for obj in objects:
        update_knit(obj, depsgraph)


_temporaries = itertools.count()


def temporary_sibling(path):
    """The hidden sibling `.NAME.PID.N.tmp` that libknit's writers use for `path` (the name cut to
    fit the 255-byte limit): a Blender killed mid-bake leaves it hidden, and the next bake into that
    folder (bake_pc2, through knit.remove_stale_temporaries) or any other knit write there removes
    it as stale."""
    folder, name = os.path.split(path)
    tail = f".{os.getpid()}.{next(_temporaries)}.tmp"
    encoded = name.encode()[:255 - len(tail) - 1].decode(errors="ignore")
    return os.path.join(folder, "." + encoded + tail)


def bake_pc2(context, obj, path, first, last):
    """Writes frames first..last of the knit object's points to a PC2 file; returns the frame count.
    Raises ValueError (nothing written) when a frame cannot follow the source (its status)."""
    scene = context.scene
    current = scene.frame_current
    count = len(obj.data.vertices)
    # What a bake killed before left here (its process gone), as every knit writer does.
    knit_module().remove_stale_temporaries(os.path.dirname(path))
    tmp = temporary_sibling(path)
    try:
        with open(tmp, "wb") as f:
            f.write(struct.pack("<12siiffi", b"POINTCACHE2\0", 1, count, float(first), 1.0, last - first + 1))
            co = np.empty(count * 3, dtype=np.float32)
            for frame in range(first, last + 1):
                scene.frame_set(frame)  # runs on_frame_change
                if obj.get(STATUS_PROP):
                    raise ValueError(f"frame {frame}: {obj[STATUS_PROP]}")
                obj.data.vertices.foreach_get("co", co)
                f.write(co.tobytes())
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
        scene.frame_set(current)
    return last - first + 1
