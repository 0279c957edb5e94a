# blender_import.py — imports exports with Blender's own importers (headless) and prints, per file,
# what Blender built as one line "KNIT <json>":
#   {"file", "objects", "vertices", "edges", "faces", "looseEdges", "min": [x,y,z], "max": [x,y,z],
#    "images": [[width, height], ...]}
# (images: every distinct image texture node of the mesh objects' materials)
# (bounds in Blender's world space: Z up; the OBJ and glTF importers turn Y-up files to Z-up).
#
# Usage: blender -b --factory-startup --python blender_import.py -- FILE.obj|.gltf|.glb|.ply ...
# Exits 1 when an import fails.
import json
import os
import sys

import bpy
import numpy

# Debian's Blender 3.4 glTF importer still uses numpy's `np.bool`, removed in numpy 1.24 (Debian
# ships a newer numpy): give it the alias back, or every glTF triangle import fails.
if not hasattr(numpy, "bool"):
    numpy.bool = bool


def importer(path):
    """The Blender 3.4 operator that imports `path` (by extension)."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        return lambda: bpy.ops.wm.obj_import(filepath=path)
    if ext in (".gltf", ".glb"):
        return lambda: bpy.ops.import_scene.gltf(filepath=path)
    if ext == ".ply":
        return lambda: bpy.ops.import_mesh.ply(filepath=path)
    raise ValueError("no importer for " + path)


def summarize(path):
    """Counts and world bounds of every mesh object in the scene."""
    s = {"file": path, "objects": 0, "vertices": 0, "edges": 0, "faces": 0, "looseEdges": 0}
    lo = [float("inf")] * 3
    hi = [float("-inf")] * 3
    for obj in bpy.context.scene.objects:
        if obj.type != "MESH":
            continue
        mesh = obj.data
        s["objects"] += 1
        s["vertices"] += len(mesh.vertices)
        s["edges"] += len(mesh.edges)
        s["faces"] += len(mesh.polygons)
        s["looseEdges"] += sum(1 for e in mesh.edges if e.is_loose)
        m = obj.matrix_world
        for v in mesh.vertices:
            w = m @ v.co
            for k in range(3):
                lo[k] = min(lo[k], w[k])
                hi[k] = max(hi[k], w[k])
    s["min"], s["max"] = lo, hi
    images = {}
    for obj in bpy.context.scene.objects:
        if obj.type != "MESH":
            continue
        for slot in obj.material_slots:
            if slot.material is None or not slot.material.use_nodes:
                continue
            for node in slot.material.node_tree.nodes:
                if node.type == "TEX_IMAGE" and node.image is not None:
                    images[node.image.name] = [node.image.size[0], node.image.size[1]]
    s["images"] = list(images.values())
    return s


def main(files):
    failed = False
    for path in files:
        # A fresh, empty scene per file.
        bpy.ops.wm.read_factory_settings(use_empty=True)
        try:
            importer(path)()
            print("KNIT " + json.dumps(summarize(path)), flush=True)
        except Exception as e:  # report and go on with the next file
            print("KNIT " + json.dumps({"file": path, "error": str(e)}), flush=True)
            failed = True
    return failed


argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
sys.exit(1 if main(argv) else 0)
