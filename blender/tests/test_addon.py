"""Headless test of the knit_blender add-on (run by ctest: blender -b --factory-startup
--python-exit-code 1 --python blender/tests/test_addon.py). KNIT_PYTHONPATH points at build/python.

Checks: <mesh>.knit exists, its point count is the library's, its radii are the ply radius, a frame
change (a shape key animates the base mesh) moves it, a PC2 bake has the right size, a small
Cycles render of it is not blank, and the file reopened on another frame re-binds the same pose."""
import contextlib
import io
import os
import sys
import tempfile

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import knit_blender  # noqa: E402
from addon_scene import check, make_animated_grid, points_of  # noqa: E402
from knit_blender import build  # noqa: E402


def render_coverage(obj):
    """Renders a 64x48 Cycles image (CPU, 4 samples) from above; returns (coverage, variance)."""
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False  # Debian builds Blender without OpenImageDenoise
    bpy.context.view_layer.cycles.denoising_store_passes = False
    scene.render.resolution_x, scene.render.resolution_y = 64, 48
    scene.render.resolution_percentage = 100
    scene.world = scene.world or bpy.data.worlds.new("World")
    scene.world.use_nodes = False
    scene.world.color = (0.0, 0.0, 0.0)
    bpy.data.objects["Cloth"].hide_render = True  # only the knit
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 0.6
    camera.location = (0.0, 0.0, 1.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 5.0
    scene.collection.objects.link(sun)
    path = os.path.join(tempfile.mkdtemp(), "knit.png")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    pixels = np.array(image.pixels[:]).reshape(-1, 4)[:, :3]
    luminance = pixels.mean(axis=1)
    return float((luminance > 0.02).mean()), float(luminance.var())


def check_chart_warnings():
    """A chart's designer warnings (a float longer than 5 stitches; an intarsia repeat knitted
    taller than drawn) are Apply Knit's WARNING reports, in the library's words, the knit made."""
    band = bpy.data.texts.new("band")
    band.write("k k k k k k k\n\nA B A A A A A\nA=#ffffff B=#000000\nstranded\n")
    cloth = bpy.data.objects["Cloth"]
    bpy.context.view_layer.objects.active = cloth
    out = io.StringIO()
    with contextlib.redirect_stdout(out):  # background mode prints an operator's reports
        result = bpy.ops.object.knit_apply(chart_text="band", repeats=(3, 3), plies=2)
    printed = out.getvalue()
    check(result == {"FINISHED"}, "a chart with a long float still knits")
    check("Warning: band:1: row 1: the float of colour B over columns 3-1 (round the repeat) is 6 stitches long"
          in printed, f"the long float is reported as a warning ({printed.strip()})")
    check("max_float" not in printed, f"no Python keyword in the add-on's words ({printed.strip()})")
    bpy.context.view_layer.objects.active = bpy.data.objects["Cloth.knit"]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        check(bpy.ops.object.knit_reapply() == {"FINISHED"}, "re-applied")
    check("Warning: band:1: row 1: the float" in out.getvalue(), f"Re-apply reports it too ({out.getvalue()})")
    # The stacked intarsia chart (40 s to relax: its warnings only), as text and as a chart file.
    wander = "k k k k\nk k k k\n\nB A B A\nA B A B\nA=#ffffff B=#000000\nintarsia\n"
    said = build.chart_warnings({"chart_source": wander, "chart_text": "wander", "pattern": "stockinette"})
    check(len(said) == 1 and said[0].startswith("wander: intarsia: the colour areas move round the period")
          and said[0].endswith("knitted 4 rows tall (its rows 2 times over)"), f"the stacked chart's warning ({said})")
    path = os.path.join(tempfile.mkdtemp(), "wander.chart")
    with open(path, "w") as f:
        f.write(wander)
    said = build.chart_warnings({"pattern": path})
    check(len(said) == 1 and said[0].startswith(path + ": intarsia: the colour areas move round the period"),
          f"a chart file Pattern warns the same ({said})")
    check(build.chart_warnings({"pattern": "stockinette"}) == [], "a pattern that is no chart: nothing to say")


def check_chart_text():
    """A chart in a text block (a lace row and a stranded colour row) knits as that chart; a bad
    chart or a missing block cancels with the error."""
    os.environ["KNIT_CACHE_DIR"] = tempfile.mkdtemp()
    block = bpy.data.texts.new("lace")
    block.write("k yo k2tog k\nk k k k\n\nA A A A\nA B A B\nA=#ffffff B=#1d3557\nstranded\n")
    bpy.ops.object.select_all(action="DESELECT")
    cloth = bpy.data.objects["Cloth"]
    bpy.context.view_layer.objects.active = cloth
    result = bpy.ops.object.knit_apply(chart_text="lace", repeats=(3, 3), plies=2)
    check(result == {"FINISHED"}, "knit_apply with a chart text block finished")
    obj = bpy.data.objects["Cloth.knit"]
    scene = build.scene_of(obj, bpy.context.evaluated_depsgraph_get())
    check(scene.pattern.name == "lace", f"the chart text is the pattern ({scene.pattern.name})")
    check(len(obj.data.vertices) == scene.evaluate_plies(scene.mesh.positions).point_count > 0,
          "the chart's plies are the object's points")
    bad = bpy.data.texts.new("bad")
    bad.write("k yo k k\nk k k k\n")
    try:
        bad_result = bpy.ops.object.knit_apply(chart_text="bad")
    except RuntimeError as e:  # the operator's ERROR report raises in background mode
        bad_result = str(e)
    check("bad:1:8: row consumes 3 loops" in str(bad_result), f"a bad chart is refused with its position ({bad_result})")
    try:
        missing = bpy.ops.object.knit_apply(chart_text="nope")
    except RuntimeError as e:
        missing = str(e)
    check("no text block named 'nope'" in str(missing), f"a missing text block is named ({missing})")


def main():
    knit_blender.register()
    make_animated_grid()
    result = bpy.ops.object.knit_apply(pattern="stockinette", repeats=(6, 6), plies=2, twist="S")
    check(result == {"FINISHED"}, "knit_apply finished")
    obj = bpy.data.objects.get("Cloth.knit")
    check(obj is not None, "the object Cloth.knit exists")

    scene = build.scene_of(obj, bpy.context.evaluated_depsgraph_get())
    plies = scene.evaluate_plies(scene.mesh.positions)  # the bind pose
    check(len(obj.data.vertices) == plies.point_count > 0,
          f"point count {len(obj.data.vertices)} is the library's {plies.point_count}")
    radius = np.empty(len(obj.data.vertices), dtype=np.float32)
    obj.data.attributes["radius"].data.foreach_get("value", radius)
    check(np.allclose(radius, scene.ply_radius, rtol=1e-6), f"radii are the ply radius {scene.ply_radius:.6g}")
    check(np.array_equal(points_of(obj), plies.points.astype(np.float32)), "points are the library's plies")
    check(obj.modifiers[0].type == "NODES", "a geometry-nodes modifier renders the curves")
    # One UV island: the UVs are welded per vertex, so no yarn is cut (and re-welded) at a triangle edge.
    # (One UV per loop made every triangle edge a seam: 784 welded ends on this grid at repeats (6, 6).)
    check(scene.stats["welded_ends"] == 0, f"no seam inside the grid (welded ends {scene.stats['welded_ends']})")

    rest = points_of(obj)
    bpy.context.scene.frame_set(10)
    moved = points_of(obj)
    lift = float((moved[:, 2] - rest[:, 2]).max())
    check(0.08 < lift < 0.12, f"frame 10 lifts the knit with the shape key ({lift:.4f} m)")
    bpy.context.scene.frame_set(1)
    check(np.array_equal(points_of(obj), rest), "frame 1 brings it back exactly (frames are history-free)")

    path = os.path.join(tempfile.mkdtemp(), "knit.pc2")
    bpy.ops.object.select_all(action="DESELECT")
    bpy.context.view_layer.objects.active = obj
    check(bpy.ops.object.knit_bake_pc2(filepath=path, frame_start=1, frame_end=3) == {"FINISHED"}, "PC2 bake finished")
    check(os.path.getsize(path) == 32 + 3 * len(obj.data.vertices) * 12, "PC2 file holds 3 frames of every point")

    coverage, variance = render_coverage(obj)
    check(coverage > 0.2 and variance > 1e-4, f"Cycles render is not blank (coverage {coverage:.2f}, variance {variance:.2g})")
    # Reopened on another frame (a new session has no bound scenes): re-bound on the stored bind
    # pose, not on the frame the file opens on, so frame 10 is what it was.
    bpy.context.scene.frame_set(10)
    blend = os.path.join(tempfile.mkdtemp(), "knit.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    # This session's Cloth.knit then bound otherwise: the file's knit is not that one (the session's
    # bound scenes are forgotten when a file is opened; before, the file's knit took 8 x 8's plies).
    bpy.context.view_layer.objects.active = bpy.data.objects["Cloth"]
    check(bpy.ops.object.knit_apply(pattern="stockinette", repeats=(8, 8)) == {"FINISHED"}, "re-applied at 8 x 8")
    bpy.ops.wm.open_mainfile(filepath=blend)
    bpy.context.scene.frame_set(10)
    obj = bpy.data.objects["Cloth.knit"]
    check(np.array_equal(points_of(obj), moved), "reopened on frame 10 and re-bound: frame 10 is unchanged")
    check_chart_text()
    check_chart_warnings()
    print("knit_blender: all checks passed")


main()
