#!/usr/bin/env python3
"""check_clients.py — real clients open libknit's exports and see what was written.

Steps: (1) export a small scene (--mesh-res 8, 4 x 4 repeats) in every format a client reads;
(2) read what each file declares (OBJ/PLY records, glTF accessors and node transforms) and the
CLI's export report; (3) load the files in the client (three.js under node: every glTF/GLB,
Draco and meshopt included; Blender 3.4 headless: every uncompressed OBJ/PLY/glTF/GLB);
(4) compare counts (vertices, triangles, curves) and world bounds, and check the up axis.

Usage: check_clients.py --client threejs|blender --knit KNIT --work DIR
                        [--node-modules DIR] [--node NODE] [--blender BLENDER]
Exit status: 0 = all agree, 1 = a mismatch or failure, 77 = the client is not installed (skip;
with CI=true a missing client is a failure instead).
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = ["build", "-q", "--mesh-res", "8", "--repeats", "4", "4"]

# (file name, extra CLI arguments, compressed: only three.js decodes it)
EXPORTS = [
    ("plies.obj", [], False),
    ("yarns.obj", ["--export", "yarns"], False),
    ("tubes.obj", ["--export", "tubes", "--sides", "5"], False),
    ("plies.ply", [], False),
    ("tubes.ply", ["--export", "tubes"], False),
    ("plies.glb", [], False),
    ("plies.gltf", [], False),
    ("tubes.glb", ["--export", "tubes"], False),
    ("tubes.gltf", ["--export", "tubes", "--yarn-colors"], False),
    ("tubes_quantized.glb", ["--export", "tubes", "--quantize"], False),
    ("tubes_draco.glb", ["--export", "tubes", "--draco"], True),
    ("tubes_meshopt.glb", ["--export", "tubes", "--meshopt"], True),
    ("tubes_quantized_meshopt.glb", ["--export", "tubes", "--quantize", "--meshopt", "--yarn-colors"], True),
    ("cylinder_tubes.glb", ["--mesh", "cylinder", "--export", "tubes", "--quantize", "--meshopt"], True),
    ("cylinder_plies.obj", ["--mesh", "cylinder"], False),
    # The surface level: the base mesh with the baked knit material (embedded PNG textures).
    ("surface.glb", ["--surface-only", "--bake-size", "16"], False),
    # A view (`--detail view`): far (every cell at the surface level: the textured base mesh only)
    # and grazing over a plane (plies of the near cells and the textured surface of the far ones,
    # in one file).
    ("view_far.glb", ["--detail", "view", "--width", "8", "--height", "6", "--bake-size", "16"], False),
    ("view_mixed.glb", ["--mesh", "plane", "--detail", "view", "--eye", "0.24", "0.01", "0.24", "--target", "-0.2",
                        "0", "-0.2", "--width", "8", "--height", "8", "--bake-size", "16"], False),
]


def in_ci():
    return os.environ.get("CI", "") in ("true", "1")


def skip_or_fail(message):
    if in_ci():
        print("FAIL (CI=true): " + message)
        sys.exit(1)
    print("SKIP: " + message)
    sys.exit(77)


# ---- step 2: what each file declares -------------------------------------------------------

def bounds_of(points):
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return lo, hi


def read_obj(path):
    points, lines, faces = [], 0, 0
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                points.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("l "):
                assert len(line.split()) == 3, "OBJ curves must be 2-index `l i j` segments: " + line
                lines += 1
            elif line.startswith("f "):
                faces += 1
    lo, hi = bounds_of(points)
    return {"vertices": len(points), "segments": lines, "triangles": faces, "min": lo, "max": hi}


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    elements, props = {}, []
    for line in data[:end].decode().splitlines():
        w = line.split()
        if w[0] == "element":
            elements[w[1]] = int(w[2])
            current = w[1]
        elif w[0] == "property" and current == "vertex":
            props.append(w[1])
    sizes = {"double": 8, "float": 4}
    stride = sum(sizes[p] for p in props)
    assert props[:3] == ["double"] * 3, "PLY positions are expected as doubles"
    n = elements["vertex"]
    points = [struct.unpack_from("<3d", data, end + i * stride) for i in range(n)]
    lo, hi = bounds_of(points)
    return {"vertices": n, "segments": elements.get("edge", 0), "triangles": elements.get("face", 0),
            "min": lo, "max": hi}


def gltf_json(path):
    with open(path, "rb") as f:
        data = f.read()
    if path.endswith(".glb"):
        size = struct.unpack_from("<I", data, 12)[0]
        return json.loads(data[20:20 + size])
    return json.loads(data)


def read_gltf(path):
    """Counts and world bounds from the accessors and the nodes (translation + uniform scale)."""
    doc = gltf_json(path)
    acc = doc["accessors"]
    r = {"vertices": 0, "triangles": 0, "lines": 0, "lineVertices": 0,
         "min": [float("inf")] * 3, "max": [float("-inf")] * 3}
    for node in doc["nodes"]:
        if "mesh" not in node:
            continue
        t = node.get("translation", [0, 0, 0])
        s = node.get("scale", [1, 1, 1])
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            pos = acc[prim["attributes"]["POSITION"]]
            mode = prim.get("mode", 4)
            if mode == 4:
                r["vertices"] += pos["count"]
                r["triangles"] += (acc[prim["indices"]]["count"] if "indices" in prim else pos["count"]) // 3
            elif mode == 3:
                r["lines"] += 1
                r["lineVertices"] += pos["count"]
            for k in range(3):
                r["min"][k] = min(r["min"][k], t[k] + s[k] * pos["min"][k])
                r["max"][k] = max(r["max"][k], t[k] + s[k] * pos["max"][k])
    return r


def declared(path):
    if path.endswith(".obj"):
        return read_obj(path)
    if path.endswith(".ply"):
        return read_ply(path)
    return read_gltf(path)


# ---- step 4: comparisons --------------------------------------------------------------------

class Checker:
    def __init__(self):
        self.failures = []

    def eq(self, what, got, want):
        if got != want:
            self.failures.append("%s: client has %s, file has %s" % (what, got, want))

    def box(self, what, got_lo, got_hi, want_lo, want_hi):
        extent = max(h - l for l, h in zip(want_lo, want_hi))
        tol = 1e-5 * extent + 1e-6
        for k in range(3):
            if abs(got_lo[k] - want_lo[k]) > tol or abs(got_hi[k] - want_hi[k]) > tol:
                self.failures.append("%s bounds: client %s..%s, file %s..%s" % (what, got_lo, got_hi, want_lo, want_hi))
                return

    def up(self, what, name, lo, hi, up_axis):
        """Built-in meshes are +Y up: the drape lies flat (thinnest along up), the cylinder stands."""
        ext = [h - l for l, h in zip(lo, hi)]
        others = [ext[k] for k in range(3) if k != up_axis]
        if name.startswith("cylinder"):
            ok = ext[up_axis] > max(others)
        else:
            ok = ext[up_axis] < 0.5 * min(others)
        if not ok:
            self.failures.append("%s: up axis is not %s (extents %s)" % (what, "xyz"[up_axis], ext))


def y_up_to_blender(lo, hi):
    """Blender's OBJ and glTF importers turn Y-up into Z-up: (x, y, z) -> (x, -z, y)."""
    return [lo[0], -hi[2], lo[1]], [hi[0], -lo[2], hi[1]]


def run_client(client, command, files, prefix, checker, env=None):
    """Runs the client on `files`; yields (path, name, summary) for every file it loaded (the
    summaries are JSON lines starting with `prefix`), a failure for every other."""
    out = subprocess.run(command + files, capture_output=True, text=True, timeout=600, env=env)
    seen = {}
    for line in out.stdout.splitlines():
        if line.startswith(prefix):
            s = json.loads(line[len(prefix):])
            seen[os.path.basename(s["file"])] = s
    for f in files:
        name = os.path.basename(f)
        s = seen.get(name)
        if s is None or "error" in s:
            detail = (s or {}).get("error", (out.stdout + out.stderr)[-2000:])
            checker.failures.append("%s could not load %s: %s" % (client, name, detail))
            continue
        yield f, name, s


def check_threejs(args, files, reports, checker):
    modules = args.node_modules
    node = args.node or shutil.which("node")
    if not node:
        skip_or_fail("node is not installed")
    if not modules or not os.path.isfile(os.path.join(modules, "three", "package.json")):
        skip_or_fail("three.js is not installed in %s (cmake --build <build> --target three_js)" % modules)
    gltfs = [f for f in files if f.endswith((".glb", ".gltf"))]
    command = [node, os.path.join(HERE, "three_load.mjs"), modules]
    for f, name, s in run_client("three.js", command, gltfs, "KNIT ", checker):
        want = declared(f)
        for key in ("vertices", "triangles", "lines", "lineVertices"):
            checker.eq("three.js %s %s" % (name, key), s[key], want[key])
        stats = reports[name]
        # A view's surface level is counted apart from its curves (export.surface).
        meshes = stats.get("surface", stats)
        if want["triangles"]:
            checker.eq("three.js %s vertices vs report" % name, s["vertices"], meshes["vertices"])
            checker.eq("three.js %s triangles vs report" % name, s["triangles"], meshes["triangles"])
        if not want["triangles"] or "surface" in stats:
            checker.eq("three.js %s curves vs report" % name, s["lines"], stats["curves"])
        checker.box("three.js " + name, s["min"], s["max"], want["min"], want["max"])
        checker.up("three.js " + name, name, s["min"], s["max"], 1)
        if "bakeWidth" in meshes:
            check_baked_material("three.js " + name, s, meshes, checker)
    return len(gltfs)


def check_baked_material(what, s, stats, checker):
    """The surface level's material: albedo and normal maps of the baked size, repeating
    (three.js RepeatWrapping = 1000), alpha MASK at 0.5 (alphaTest, not transparent)."""
    slots = {t["slot"]: t for t in s.get("textures", [])}
    for slot in ("map", "normalMap"):
        t = slots.get(slot)
        if t is None:
            checker.failures.append("%s: the material has no %s" % (what, slot))
            continue
        checker.eq("%s %s size" % (what, slot), [t["width"], t["height"]], [stats["bakeWidth"], stats["bakeHeight"]])
        checker.eq("%s %s wrap" % (what, slot), [t["wrapS"], t["wrapT"]], [1000, 1000])
    checker.eq("%s alphaTest" % what, s.get("alphaTest"), 0.5)
    checker.eq("%s transparent" % what, s.get("transparent"), False)


def check_blender(args, files, compressed, reports, checker):
    blender = args.blender or shutil.which("blender")
    if not blender:
        skip_or_fail("blender is not installed")
    plain = [f for f in files if f not in compressed]
    # Debian's Blender finds its system Python (numpy, for the glTF importer) through the python3
    # on PATH: put Blender's own folder first, so a pyenv/venv python3 running this script is not it.
    env = dict(os.environ, PATH=os.path.dirname(os.path.realpath(blender)) + os.pathsep + os.environ.get("PATH", ""))
    command = [blender, "-b", "--factory-startup", "--python", os.path.join(HERE, "blender_import.py"), "--"]
    for f, name, s in run_client("Blender", command, plain, "KNIT ", checker, env):
        want = declared(f)
        checker.eq("Blender %s vertices" % name, s["vertices"], want["vertices"] + want.get("lineVertices", 0))
        if f.endswith((".obj", ".ply")):
            checker.eq("Blender %s faces" % name, s["faces"], want["triangles"])
            if not want["triangles"]:
                checker.eq("Blender %s edges (every curve segment)" % name, s["edges"], want["segments"])
        else:
            checker.eq("Blender %s faces" % name, s["faces"], want["triangles"])
            if want["lines"] and not want["triangles"]:
                checker.eq("Blender %s edges (every curve segment)" % name, s["edges"],
                           want["lineVertices"] - want["lines"])
            elif want["lines"]:  # curves beside a surface: the curve segments are the loose edges
                checker.eq("Blender %s loose edges (every curve segment)" % name, s["looseEdges"],
                           want["lineVertices"] - want["lines"])
            meshes = reports[name].get("surface", reports[name])
            if "bakeWidth" in meshes:  # the baked material: its two images, as baked
                checker.eq("Blender %s material images" % name, sorted(s.get("images", [])),
                           [[meshes["bakeWidth"], meshes["bakeHeight"]]] * 2)
        lo, hi = want["min"], want["max"]
        up = 1
        if not f.endswith(".ply"):  # Blender's PLY importer keeps the file's axes
            lo, hi = y_up_to_blender(lo, hi)
            up = 2
        checker.box("Blender " + name, s["min"], s["max"], lo, hi)
        checker.up("Blender " + name, name, s["min"], s["max"], up)
    return len(plain)


def export_all(args):
    """Step 1: the exports, each with its CLI report."""
    os.makedirs(args.work, exist_ok=True)
    files, compressed, reports = [], set(), {}
    for name, extra, packed in EXPORTS:
        path = os.path.join(args.work, name)
        report = path + ".json"
        subprocess.run([args.knit] + SCENE + extra + ["-o", path, "--report", report], check=True,
                       capture_output=True)
        with open(report) as f:
            reports[name] = json.load(f)["export"]
        files.append(path)
        if packed:
            compressed.add(path)
    return files, compressed, reports


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--client", choices=["threejs", "blender"], required=True)
    p.add_argument("--knit", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--node-modules")
    p.add_argument("--node")
    p.add_argument("--blender")
    args = p.parse_args()
    checker = Checker()
    files, compressed, reports = export_all(args)
    if args.client == "threejs":
        n = check_threejs(args, files, reports, checker)
    else:
        n = check_blender(args, files, compressed, reports, checker)
    for failure in checker.failures:
        print("MISMATCH " + failure)
    print("%s: %d files checked, %d mismatches" % (args.client, n, len(checker.failures)))
    return 1 if checker.failures else 0


if __name__ == "__main__":
    sys.exit(main())
