"""What the headless add-on tests share: the animated grid they drape the knit on, reading an
object's points, and printing a check."""
import bpy
import numpy as np


def make_animated_grid():
    """A 0.5 m grid with UVs in the XY plane, named Cloth; a shape key 'Bulge' lifts it by up to
    0.1 m, keyed 0 at frame 1 and 1 at frame 10."""
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.object.delete()
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=16, y_subdivisions=16, size=0.5, calc_uvs=True)
    grid = bpy.context.active_object
    grid.name = "Cloth"
    grid.shape_key_add(name="Basis")
    bulge = grid.shape_key_add(name="Bulge")
    for p in bulge.data:
        p.co.z += 0.1 * max(0.0, 1.0 - (p.co.x ** 2 + p.co.y ** 2) / 0.0625)
    bulge.value = 0.0
    bulge.keyframe_insert("value", frame=1)
    bulge.value = 1.0
    bulge.keyframe_insert("value", frame=10)
    bpy.context.scene.frame_set(1)
    return grid


def points_of(obj):
    co = np.empty(len(obj.data.vertices) * 3, dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        raise SystemExit(f"knit_blender test failed: {what}")
