"""Per-frame update time of the knit_blender add-on on a ~1M-ply-point object (issue 14 target:
<= 0.5 s on 2 cores). Run headless:

    KNIT_PYTHONPATH=build/python blender -b --factory-startup --python tools/blender_frame_timing.py

Builds a 128x128 grid with a shape key, applies the knit with repeats chosen for ~1M ply points,
then times frame changes: the add-on's handler alone (read the evaluated mesh, evaluate_plies,
foreach_set) and the whole frame_set (which also evaluates the depsgraph, without the modifier's
tubes, which Blender builds only for display or render).
"""
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "blender"))
import knit_blender  # noqa: E402
from knit_blender import build  # noqa: E402

knit_blender.register()
bpy.ops.object.select_all(action="SELECT")
bpy.ops.object.delete()
bpy.ops.mesh.primitive_grid_add(x_subdivisions=128, y_subdivisions=128, size=0.5, calc_uvs=True)
grid = bpy.context.active_object
grid.shape_key_add(name="Basis")
key = grid.shape_key_add(name="Lift")
for p in key.data:
    p.co.z += 0.05 * p.co.x
key.value = 0.0
key.keyframe_insert("value", frame=1)
key.value = 1.0
key.keyframe_insert("value", frame=20)
bpy.context.scene.frame_set(1)

target, repeats = 1_000_000, 60.0
bpy.ops.object.knit_apply(pattern="stockinette", repeats=(repeats, repeats), plies=2)
obj = bpy.data.objects[grid.name + ".knit"]
repeats *= (target / len(obj.data.vertices)) ** 0.5
bpy.ops.object.select_all(action="DESELECT")
bpy.context.view_layer.objects.active = grid
bpy.ops.object.knit_apply(pattern="stockinette", repeats=(repeats, repeats), plies=2)
obj = bpy.data.objects[grid.name + ".knit"]
obj.modifiers[0].show_viewport = False  # time the add-on, not the tube meshing
print(f"knit object: {len(obj.data.vertices)} ply points")

depsgraph = bpy.context.evaluated_depsgraph_get()
handler, whole = [], []
for frame in range(2, 12):
    t = time.perf_counter()
    bpy.context.scene.frame_set(frame)
    whole.append(time.perf_counter() - t)
    t = time.perf_counter()
    build.update_knit(obj, bpy.context.evaluated_depsgraph_get())
    handler.append(time.perf_counter() - t)
print(f"handler (read mesh + evaluate_plies + foreach_set): best {min(handler) * 1e3:.0f} ms, "
      f"median {sorted(handler)[len(handler) // 2] * 1e3:.0f} ms")
print(f"frame_set (depsgraph + handler): best {min(whole) * 1e3:.0f} ms, median {sorted(whole)[len(whole) // 2] * 1e3:.0f} ms")
