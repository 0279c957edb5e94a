"""Headless test of the add-on when a knit's source no longer matches its binding (run by ctest as
blender_addon_stale_source: blender -b --factory-startup --python-exit-code 1 --python ...).

For a Decimate modifier (vertex count), an edited and another active UV map, the module knit
missing and the source deleted: the frame handler raises nothing (no traceback), the knit keeps
its last good shape, its status says why (printed once, not on every frame), the knit follows
again when the cause is undone, and Re-apply Knit binds it to the source as it is. Operator errors
name the operator's properties, not a command line flag or a Python keyword."""
import contextlib
import io
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import knit_blender  # noqa: E402
from addon_scene import make_animated_grid, points_of  # noqa: E402
from knit_blender import build  # noqa: E402


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        raise SystemExit(f"knit_blender test failed: {what}")


def frames(first, last):
    """Sets frames first..last and calls the handler directly too (an exception from it fails the
    test here; from frame_set Blender would only print its traceback); returns what was printed."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        for f in range(first, last + 1):
            bpy.context.scene.frame_set(f)
            build.on_frame_change(bpy.context.scene, bpy.context.evaluated_depsgraph_get())
    return out.getvalue()


def expect_stale(obj, shape, printed, words, what, reapply=True):
    status = obj.get(build.STATUS_PROP, "")
    check(all(w in status for w in words), f"{what}: the status says why ({status!r})")
    check(("Re-apply" in status) == reapply, f"{what}: the status offers Re-apply where it helps")
    check(printed.count("knit: warning:") == 1, f"{what}: said once over 3 frames ({printed.count('knit: warning:')})")
    check(np.array_equal(points_of(obj), shape), f"{what}: the knit keeps its last good shape")


def expect_following(obj, what):
    check(obj.get(build.STATUS_PROP, "") == "", f"{what}: no status")
    scene = build.scene_of(obj, bpy.context.evaluated_depsgraph_get())
    expected = scene.evaluate_plies(build.read_positions(bpy.data.objects["Cloth"],
                                                        bpy.context.evaluated_depsgraph_get()))
    check(np.array_equal(points_of(obj), expected.points.astype(np.float32)), f"{what}: the knit follows its source")


def main():
    knit_blender.register()
    cloth = make_animated_grid()
    check(bpy.ops.object.knit_apply(pattern="stockinette", repeats=(6, 6)) == {"FINISHED"}, "knit_apply finished")
    obj = bpy.data.objects["Cloth.knit"]
    frames(1, 5)
    shape = points_of(obj)

    # Decimate: fewer vertices than the binding's (a traceback on every frame before).
    decimate = cloth.modifiers.new("Decimate", "DECIMATE")
    decimate.ratio = 0.5
    expect_stale(obj, shape, frames(6, 8), ["vertices", "bound to 289", "Decimate"], "Decimate")
    cloth.modifiers.remove(decimate)
    frames(9, 9)
    expect_following(obj, "Decimate removed")
    shape = points_of(obj)

    # The active UV map edited, then another one made active.
    uv = cloth.data.uv_layers.active
    saved = np.empty(len(uv.data) * 2, dtype=np.float32)
    uv.data.foreach_get("uv", saved)
    uv.data.foreach_set("uv", saved * 2.0)
    cloth.data.update()
    expect_stale(obj, shape, frames(6, 8), ["UV map", "changed"], "UV map edited")
    uv.data.foreach_set("uv", saved)
    cloth.data.update()
    frames(9, 9)
    expect_following(obj, "UV map restored")
    shape = points_of(obj)
    other = cloth.data.uv_layers.new(name="Other")  # a copy of the active map's UVs, then moved
    other.data.foreach_set("uv", saved * 0.5)
    cloth.data.uv_layers.active = other
    expect_stale(obj, shape, frames(6, 8), ["active UV map is now Other"], "another UV map active")
    cloth.data.uv_layers.remove(cloth.data.uv_layers["Other"])
    cloth.data.uv_layers.active = cloth.data.uv_layers[0]
    frames(9, 9)
    expect_following(obj, "first UV map active again")
    shape = points_of(obj)

    # Renaming the UV map keeps its coordinates: the knit follows; removing it does not.
    uv.name = "Sleeve UVs"
    out = frames(6, 8)
    check("knit: warning" not in out, f"UV map renamed: no warning ({out.strip()})")
    expect_following(obj, "UV map renamed")
    uv.name = "UVMap"
    shape = points_of(obj)

    # A shape key moving a vertex to NaN: named as the source's vertex, not the module's argument.
    bulge = cloth.data.shape_keys.key_blocks["Bulge"]
    saved_co = tuple(bulge.data[5].co)
    bulge.data[5].co = (float("nan"), 0.0, 0.0)
    expect_stale(obj, shape, frames(10, 12), ["the source's vertex 5", "not finite"], "a NaN vertex")
    check("positions" not in obj.get(build.STATUS_PROP, ""), "a NaN vertex: no Python keyword in the status")
    bulge.data[5].co = saved_co
    frames(9, 9)
    expect_following(obj, "the NaN vertex restored")
    shape = points_of(obj)

    # The source renamed: the knit is parented to it, so it follows it under its new name.
    cloth.name = "Shirt"
    out = frames(6, 8)
    check("knit: warning" not in out and obj[build.SOURCE_PROP] == "Shirt",
          f"source renamed: followed, its new name recorded ({out.strip()})")
    cloth.name = "Cloth"
    frames(9, 9)
    shape = points_of(obj)

    # The module knit missing (an add-on installed without it, or a broken install).
    saved_module = sys.modules.get("knit")
    sys.modules["knit"] = None  # `import knit` raises ImportError
    try:
        expect_stale(obj, shape, frames(6, 8), ["module knit was not found", "Module folder"], "module missing",
                     reapply=False)
        check("--" not in obj.get(build.STATUS_PROP, ""), "module missing: no command line in the status")
        bpy.context.view_layer.objects.active = obj
        try:
            bpy.ops.object.knit_reapply()
            check(False, "Re-apply without the module is refused")
        except RuntimeError as e:
            check("module knit was not found" in str(e), f"Re-apply without the module says so ({e})")
    finally:
        sys.modules["knit"] = saved_module
    frames(9, 9)
    expect_following(obj, "module back")

    # Re-apply after a Subdivision Surface (more vertices, the same topology on every frame; a
    # Decimate of the animated grid changes its topology from frame to frame, so no binding can
    # follow it): bound to the subdivided source, it follows it.
    subdivision = cloth.modifiers.new("Subdivision", "SUBSURF")
    subdivision.levels = 1
    frames(6, 6)
    check("vertices" in obj.get(build.STATUS_PROP, ""), "Subdivision Surface: stale until re-applied")
    bpy.context.view_layer.objects.active = obj
    check(bpy.ops.object.knit_reapply() == {"FINISHED"}, "Re-apply Knit finished")
    obj = bpy.data.objects["Cloth.knit"]
    out = frames(7, 9)
    check("knit: warning" not in out, f"after Re-apply: no warning ({out.strip()})")
    expect_following(obj, "re-applied to the subdivided source")
    check(len(obj.data.vertices) > len(shape), "the re-applied knit has more ply points (a finer source)")
    cloth.modifiers.remove(subdivision)
    frames(9, 9)
    check("vertices" in obj.get(build.STATUS_PROP, ""), "Subdivision Surface removed: stale again")

    # Operator errors in the operator's property names; a failed Apply leaves the knit as it was.
    obj = bpy.data.objects["Cloth.knit"]
    frames(5, 5)
    shape = points_of(obj)
    bpy.context.view_layer.objects.active = cloth
    for kwargs, name in [(dict(repeats=(1e6, 1e6)), "Repeats"), (dict(repeats=(6, 6), ply_pitch=1e-12), "Ply pitch")]:
        try:
            bpy.ops.object.knit_apply(pattern="stockinette", **kwargs)
            check(False, f"knit_apply {kwargs} is refused")
        except RuntimeError as e:
            message = str(e)
            check(f"({name})" in message and "--" not in message and "max_memory" not in message
                  and "(repeats)" not in message and "(ply_pitch)" not in message,
                  f"knit_apply {kwargs}: named by the property ({message.strip()})")

    check(bpy.data.objects.get("Cloth.knit") == obj and np.array_equal(points_of(obj), shape),
          "the failed Apply left the previous knit as it was")

    # The source deleted: the knit stays as it was, says so, and Re-apply refuses clearly.
    world = obj.matrix_world.copy()
    bpy.data.objects.remove(cloth)
    obj.matrix_world = world
    expect_stale(obj, shape, frames(6, 8), ["source mesh 'Cloth' was deleted"], "source deleted")
    bpy.context.view_layer.objects.active = obj
    try:
        bpy.ops.object.knit_reapply()
        check(False, "Re-apply without a source is refused")
    except RuntimeError as e:
        check("no longer exists" in str(e), f"Re-apply without a source says so ({str(e).strip()})")
    print("knit_blender stale source: all checks passed")


main()
