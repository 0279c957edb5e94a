# Run by blender_mesh_cache_test.cpp:
#   blender -b --factory-startup --python-exit-code 1 --python blender_mesh_cache.py -- \
#       TOPOLOGY.obj CACHE.pc2 START_FRAME FRAME_PATTERN FIRST LAST
# Imports the topology OBJ (no axis conversion), adds a Mesh Cache modifier reading the PC2 with
# frame_start = START_FRAME, and checks that at every scene frame k in FIRST..LAST the evaluated
# vertices equal the vertices of FRAME_PATTERN % k (the library's frame k) within float tolerance.
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
topology, cache, start, pattern, first, last = args[0], args[1], float(args[2]), args[3], int(args[4]), int(args[5])


def obj_vertices(path):
    with open(path) as f:
        return [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]


bpy.ops.wm.obj_import(filepath=topology, forward_axis='Y', up_axis='Z')
ob = bpy.context.selected_objects[0]
mod = ob.modifiers.new("knit", 'MESH_CACHE')
mod.cache_format = 'PC2'
mod.filepath = cache
mod.forward_axis = 'POS_Y'
mod.up_axis = 'POS_Z'
mod.frame_start = start
worst = 0.0
for k in range(first, last + 1):
    bpy.context.scene.frame_set(k)
    mesh = ob.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    expected = obj_vertices(pattern % k)
    if len(mesh.vertices) != len(expected):
        raise SystemExit("frame %d: %d vertices in Blender, %d expected" % (k, len(mesh.vertices), len(expected)))
    for v, e in zip(mesh.vertices, expected):
        worst = max(worst, max(abs(v.co[i] - e[i]) for i in range(3)))
print("KNIT_MESH_CACHE_MAX_ERROR %.3g" % worst)
if worst > 1e-6:
    raise SystemExit("Mesh Cache differs from the library's frames by %g" % worst)
