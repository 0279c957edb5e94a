"""Headless test: the add-on's frame k is `knit animate`'s frame k (run by ctest as
blender_addon_matches_knit_animate; KNIT_PYTHONPATH points at build/python, KNIT_CLI at the knit
command line).

The add-on drapes a knit on the animated grid (a shape key bulges it over frames 1..10) and bakes
its points to PC2. The same frames of the grid, as the add-on reads them (evaluated mesh: float32
positions, loop triangles, the active UV map per loop), are written to OBJ files whose numbers
read back exactly, and `knit animate` animates them with the same options into its own PC2. The
two caches must be equal bit for bit: both are float32 roundings of the same Animator's points."""
import os
import subprocess
import sys
import tempfile

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import knit_blender  # noqa: E402
from addon_scene import make_animated_grid  # noqa: E402

FIRST, LAST = 1, 10
OPTIONS = dict(pattern="stockinette", repeats=(6, 6), plies=3, twist="Z")


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        raise SystemExit(f"knit_blender test failed: {what}")


def write_frame_obj(obj, path):
    """The evaluated mesh as the add-on passes it to knit.Mesh: v per vertex, vt per loop, one
    f per loop triangle. Coordinates are float32 values written with Python's round-trip repr."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        mesh.calc_loop_triangles()
        co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
        uv = np.empty(len(mesh.loops) * 2, dtype=np.float32)
        mesh.uv_layers.active.data.foreach_get("uv", uv)
        tris = len(mesh.loop_triangles)
        faces = np.empty(tris * 3, dtype=np.int64)
        mesh.loop_triangles.foreach_get("vertices", faces)
        loops = np.empty(tris * 3, dtype=np.int64)
        mesh.loop_triangles.foreach_get("loops", loops)
    finally:
        evaluated.to_mesh_clear()
    lines = ["v %r %r %r" % tuple(float(c) for c in p) for p in co.reshape(-1, 3)]
    lines += ["vt %r %r" % tuple(float(c) for c in t) for t in uv.reshape(-1, 2)]
    lines += ["f %d/%d %d/%d %d/%d" % (f[0] + 1, t[0] + 1, f[1] + 1, t[1] + 1, f[2] + 1, t[2] + 1)
              for f, t in zip(faces.reshape(-1, 3), loops.reshape(-1, 3))]
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


def read_pc2(path):
    with open(path, "rb") as f:
        header = f.read(32)
        points, frames = int.from_bytes(header[16:20], "little"), int.from_bytes(header[28:32], "little")
        data = np.frombuffer(f.read(), dtype="<f4")
    check(data.size == points * frames * 3, f"{os.path.basename(path)} holds {frames} frames of {points} points")
    return data.reshape(frames, points, 3)


def main():
    cli = os.environ.get("KNIT_CLI")
    if not cli or not os.path.isfile(cli):
        raise SystemExit("KNIT_CLI must name the knit command line (ctest sets it; build the knit_cli target)")
    knit_blender.register()
    grid = make_animated_grid()
    check(bpy.ops.object.knit_apply(**OPTIONS) == {"FINISHED"}, "knit_apply finished")
    obj = bpy.data.objects["Cloth.knit"]
    folder = tempfile.mkdtemp()

    # The add-on's frames, baked.
    addon_pc2 = os.path.join(folder, "addon.pc2")
    bpy.ops.object.select_all(action="DESELECT")
    bpy.context.view_layer.objects.active = obj
    result = bpy.ops.object.knit_bake_pc2(filepath=addon_pc2, frame_start=FIRST, frame_end=LAST)
    check(result == {"FINISHED"}, "the add-on baked its frames")

    # The same frames of the grid as OBJ files, animated by knit animate.
    for k in range(FIRST, LAST + 1):
        bpy.context.scene.frame_set(k)
        write_frame_obj(grid, os.path.join(folder, "frame_%04d.obj" % k))
    cli_pc2 = os.path.join(folder, "cli.pc2")
    run = subprocess.run([cli, "animate", "-q", "--no-stats", "--frames", os.path.join(folder, "frame_%04d.obj"),
                          "--pattern", OPTIONS["pattern"], "--repeats", *map(str, OPTIONS["repeats"]),
                          "--plies", str(OPTIONS["plies"]), "--twist", OPTIONS["twist"], "-o", cli_pc2],
                         capture_output=True, text=True)
    check(run.returncode == 0, f"knit animate ran ({run.stderr.strip()[-300:]})")

    addon, animate = read_pc2(addon_pc2), read_pc2(cli_pc2)
    check(addon.shape == animate.shape, f"the same frames and points ({addon.shape} and {animate.shape})")
    for k in range(LAST - FIRST + 1):
        differs = int(np.count_nonzero((addon[k] != animate[k]).any(axis=1)))
        largest = float(np.abs(addon[k].astype(np.float64) - animate[k]).max())
        check(differs == 0, f"frame {FIRST + k}: the add-on's points equal knit animate's bit for bit "
                            f"({differs} differ, largest difference {largest:.3g} m)")
    lift = float((animate[-1][:, 2] - animate[0][:, 2]).max())
    check(lift > 0.08, f"the frames move ({lift:.3f} m), so the equality is not of one pose")
    print("knit_blender matches knit animate: all checks passed")


main()
