#!/usr/bin/env python3
"""Hostile-input hunt over every `knit` subcommand (issue 29), as a new user who types anything.

Each case runs in a fresh folder holding a few small valid inputs (a pattern, a mesh with UVs, a
frame sequence, a bound scene, a point cache, a photograph) and damaged ones (empty, truncated,
binary garbage, a folder named like a file), under `timeout` and `/usr/bin/time -v`. A case is
MISHANDLED when the run
  * dies by a signal or CLI "internal error" (exit 3), or runs past the time limit (a hang);
  * peaks above 2 GB resident before it refuses;
  * exits 0 with a missing, empty or non-finite output (nan/inf in a text output);
  * refuses with a message naming a library internal (Options., ::, std::, a function()) or another
    front end's spelling (Python keywords such as res_u / max_memory, Blender property names);
  * leaves a file behind after a refusal, or any temporary after any run, or changes an input.

    /usr/bin/python3 tools/hostile_cli.py [--knit build/apps/knit/knit] [--only SUBSTRING] [--timeout 60]

prints one row per case (ok / MISHANDLED and why) and exits 1 when a case is mishandled.
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from grid_obj import grid_obj  # noqa: E402 - the tools folder first

GB = 1 << 30

# Spellings of other front ends (Python keywords, Blender property labels) and library internals.
FOREIGN = [r"\bres_u\b", r"\bmax_memory\b", r"\bclamp_tolerance\b", r"\bweld_tolerance\b", r"\bply_pitch\b",
           r"\bsamples_per_turn\b", r"\bcenter_radius\b", r"\bply_radius\b", r"\(Repeats\)", r"\(Ply pitch\)",
           r"\(Max memory\)"]
INTERNAL = [r"::", r"\bstd\b", r"\b[A-Z][A-Za-z]*(Options|Params|Info)\.\w+", r"\b[a-z]+[A-Z]\w*\(\)",
            r"basic_string", r"bad_alloc", r"vector::", r"terminate called", r"Assertion"]

# Refusals that blame the wrong thing (round 4): a material field where the user typed its flag, a
# mesh / cache / image read as a .pyp, a message whose words were pasted into the wrong slot.
MISLEADING = [(r"'(eta|alphaAlong|alphaAcross|alphaTT|kR|kTT|bodyAlbedo|reflectFraction|fiberCount|fiberTwist|"
               r"fiberShadowFloor|plyShadowFloor)'(?! \(--)", "names a material field, not the flag typed"),
              (r"\.(obj|ply|off|gltf|glb|pc2|mdd|png|exr|knitbind|npy|blend):1: data before the first block header",
               "reads another format as a .pyp"),
              (r"choose another the ", "garbled message")]


def write(path, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(path, mode) as f:
        f.write(data)


def make_fixtures(knit, root):
    """Valid small inputs made with knit itself, and damaged copies of each format."""
    run = lambda *a: subprocess.run([knit, *a], cwd=root, capture_output=True, text=True, check=True)
    write(os.path.join(root, "mesh.obj"), grid_obj())
    os.mkdir(os.path.join(root, "frames"))
    for k in range(1, 4):
        write(os.path.join(root, "frames", f"f_{k:04d}.obj"), grid_obj(z=lambda x, y, k=k: 0.02 * k * x))
    run("generate", "-o", "good.pyp")
    run("build", "-q", "--mesh", "mesh.obj", "--repeats", "2", "2", "-o", "mesh_out.ply")
    run("build", "-q", "--mesh", "plane", "--mesh-res", "2", "--repeats", "1", "1", "--export", "tubes", "-o",
        "tube.glb")
    run("build", "-q", "--mesh", "plane", "--mesh-res", "2", "--repeats", "1", "1", "--export", "tubes", "-o",
        "tube.gltf")
    run("bind", "-q", "--mesh", "mesh.obj", "--repeats", "2", "2", "-o", "good.knitbind")
    run("animate", "-q", "--no-stats", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o", "good.pc2")
    run("animate", "-q", "--no-stats", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o", "good.mdd")
    run("render", "-q", "--mesh", "plane", "--mesh-res", "2", "--repeats", "2", "2", "--width", "16", "--height",
        "12", "--spp", "1", "--output", "photo.png", "--exr", "photo.exr")
    run("render", "-q", "--mesh", "plane", "--mesh-res", "2", "--repeats", "2", "2", "--width", "1", "--height", "1",
        "--spp", "1", "--output", "tiny.png")
    run("strain-table", "-q", "--samples", "2", "2", "2", "--iterations", "5", "-o", "t.npy")
    write(os.path.join(root, "good.chart"), "k k\nk k\n")
    write(os.path.join(root, "curves.json"), '{"period": [1, 1], "radius": 0.05, "curves": '
          '[[[0, 0.5, 0], [0.5, 0.5, 0.1], [1, 0.5, 0]]]}')
    good = {"pyp": "good.pyp", "obj": "mesh.obj", "ply": "mesh_out.ply", "glb": "tube.glb", "gltf": "tube.gltf",
            "knitbind": "good.knitbind", "pc2": "good.pc2", "png": "photo.png", "exr": "photo.exr",
            "chart": "good.chart", "json": "curves.json"}
    rnd = bytes((i * 7919 + 13) % 256 for i in range(4096))
    for ext, name in good.items():
        data = open(os.path.join(root, name), "rb").read()
        write(os.path.join(root, f"empty.{ext}"), b"")
        write(os.path.join(root, f"half.{ext}"), data[: len(data) // 2])
        write(os.path.join(root, f"garbage.{ext}"), rnd)
        os.mkdir(os.path.join(root, f"dir.{ext}"))
    write(os.path.join(root, "empty.off"), b"")
    write(os.path.join(root, "garbage.off"), rnd)
    write(os.path.join(root, "garbage.npy"), rnd)
    os.mkdir(os.path.join(root, "dir.npy"))
    write(os.path.join(root, "empty.npy"), b"")
    write(os.path.join(root, "ro.txt"), "x")
    os.mkdir(os.path.join(root, "ro"))
    os.chmod(os.path.join(root, "ro"), 0o555)
    # Meshes with absurd geometry but valid syntax.
    write(os.path.join(root, "huge.obj"), grid_obj(size=1e30))
    write(os.path.join(root, "tiny.obj"), grid_obj(size=1e-30))
    write(os.path.join(root, "flat_uv.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 0 0\nvt 0 0\nf 1/1 2/2 3/3\n")
    write(os.path.join(root, "no_uv.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    write(os.path.join(root, "no_faces.obj"), "v 0 0 0\nv 1 0 0\nvt 0 0\n")
    write(os.path.join(root, "uv_huge.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1e30 0\nvt 0 1e30\n"
          "f 1/1 2/2 3/3\n")
    write(os.path.join(root, "neg_index.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
          "f -1/-1 -2/-2 -9/-9\n")
    write(os.path.join(root, "zero_index.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 0/0 1/1 2/2\n")
    # Patterns with valid syntax and absurd content.
    pyp = open(os.path.join(root, "good.pyp")).read()
    write(os.path.join(root, "notfound.pyp"), pyp.replace("\n", "\n", 1))
    # Frame sequences: one frame of another topology, a frame with a NaN.
    os.mkdir(os.path.join(root, "badframes"))
    write(os.path.join(root, "badframes", "f_0001.obj"), grid_obj())
    write(os.path.join(root, "badframes", "f_0002.obj"), grid_obj(n=3))
    os.mkdir(os.path.join(root, "nanframes"))
    write(os.path.join(root, "nanframes", "f_0001.obj"), grid_obj())
    write(os.path.join(root, "nanframes", "f_0002.obj"), grid_obj().replace("v 0.25 0.0 0.0", "v nan 0.0 0.0"))
    os.mkdir(os.path.join(root, "emptyframes"))
    # Point cache chunks.
    shutil.copy(os.path.join(root, "good.pc2"), os.path.join(root, "dup.pc2"))
    shutil.copy(os.path.join(root, "good.obj"), os.path.join(root, "dup.obj"))
    # Materials.
    write(os.path.join(root, "mat_nan.json"), '{"eta": NaN}')
    write(os.path.join(root, "mat_bad.json"), '{"eta": "glass", "kR": [1, 2]}')
    write(os.path.join(root, "mat_huge.json"), '{"eta": 1e308, "alpha_along": -5}')
    write(os.path.join(root, "mat_list.json"), '[1, 2, 3]')


def l_hexagon(fmt):
    """An L-shaped hexagon with UVs = positions (the notch is the square [0.5, 1] x [0.5, 1]) in each mesh
    format: a reader that fans it from the first corner covers the notch."""
    pts = [(0, 0), (1, 0), (1, 0.5), (0.5, 0.5), (0.5, 1), (0, 1)]
    if fmt == "obj":
        return "".join(f"v {x} {y} 0\nvt {x} {y}\n" for x, y in pts) + "f 1/1 2/2 3/3 4/4 5/5 6/6\n"
    if fmt == "off":
        return "STOFF\n6 1 0\n" + "".join(f"{x} {y} 0 {x} {y}\n" for x, y in pts) + "6 0 1 2 3 4 5\n"
    head = ("ply\nformat {} 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
            "property float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n")
    if fmt == "ply":
        return head.format("ascii") + "".join(f"{x} {y} 0 {x} {y}\n" for x, y in pts) + "6 0 1 2 3 4 5\n"
    import struct
    return (head.format("binary_little_endian").encode() +
            b"".join(struct.pack("<5f", x, y, 0, x, y) for x, y in pts) + struct.pack("<B6i", 6, 0, 1, 2, 3, 4, 5))


def make_more_fixtures(root):
    """Inputs of the fresh hunt (round 4): concave faces per format, degenerate UVs, absurd values in the
    other formats, damaged caches and curves, odd charts."""
    w = lambda name, data: write(os.path.join(root, name), data)
    for fmt in ["obj", "off", "ply"]:
        w(f"concave.{fmt}", l_hexagon(fmt))
    w("concave_bin.ply", l_hexagon("binply"))
    w("uv_nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    w("uv_zero.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float s\nproperty float t\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n")
    w("huge.off", "STOFF\n4 2 0\n0 0 0 0 0\n1e30 0 0 1 0\n1e30 1e30 0 1 1\n0 1e30 0 0 1\n3 0 1 2\n3 0 2 3\n")
    w("tiny.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float s\nproperty float t\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n0 0 0 0 0\n1e-30 0 0 1 0\n0 1e-30 0 0 1\n3 0 1 2\n")
    w("mesh.stl", grid_obj())
    w("mesh.OBJ", grid_obj())
    w("crlf.obj", grid_obj().replace("\n", "\r\n"))
    w("big_face.obj", "".join(f"v {i} {(i % 2) * 0.5} 0\nvt {i / 200000} {(i % 2) * 0.5}\n" for i in range(200000)) +
      "f " + " ".join(f"{i}/{i}" for i in range(1, 200001)) + "\n")
    w("ply_count.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n")
    # Curves JSON with absurd content.
    cj = lambda **kw: __import__("json").dumps({"period": [1, 1], "radius": 0.05,
                                                 "curves": [[[0, 0.5, 0], [0.5, 0.5, 0.1], [1, 0.5, 0]]],
                                                 **kw})
    w("c_period0.json", cj(period=[0, 1]))
    w("c_periodneg.json", cj(period=[-1, 1]))
    w("c_period_huge.json", cj(period=[1e300, 1e300]))
    w("c_radius0.json", cj(radius=0))
    w("c_nocurves.json", cj(curves=[]))
    w("c_onepoint.json", cj(curves=[[[0.5, 0.5, 0]]]))
    w("c_2d.json", cj(curves=[[[0, 0.5], [1, 0.5]]]))
    w("c_far.json", cj(curves=[[[0, 0.5, 0], [1e12, 0.5, 0]]]))
    w("c_string.json", cj(curves=[[["a", 0.5, 0], [1, 0.5, 0]]]))
    w("c_deep.json", "[" * 100000 + "]" * 100000)
    w("c_big_number.json", cj(radius=1e999).replace("Infinity", "1e999"))
    # Charts of odd bytes.
    w("nul.chart", "k k\x00\nk k\n")
    w("crlf.chart", "k k\r\nk k\r\n")
    w("tabs.chart", "k\tk\nk\tk\n")
    w("blank.chart", "\n\n   \n")
    w("utf.chart", "k \u00e9\nk k\n")
    w("one.chart", "k\n")
    # Point caches with absurd headers.
    import struct
    pc2 = open(os.path.join(root, "good.pc2"), "rb").read()
    w("huge_count.pc2", pc2[:16] + struct.pack("<i", 2_000_000_000) + pc2[20:])
    w("neg_frames.pc2", pc2[:28] + struct.pack("<i", -1) + pc2[32:])
    w("nan_fps.pc2", pc2[:24] + struct.pack("<f", float("nan")) + pc2[28:])
    w("huge_count.mdd", struct.pack(">ii", 1, 2_000_000_000) + b"\0" * 64)
    w("nan_frame.pc2", pc2[:32] + struct.pack("<f", float("nan")) + pc2[36:])
    for name in ["huge_count", "neg_frames", "nan_fps", "nan_frame"]:
        shutil.copy(os.path.join(root, "good.obj"), os.path.join(root, name + ".obj"))
    w("empty.mdd", b"")
    w("garbage.mdd", bytes((i * 31 + 7) % 256 for i in range(4096)))


SCENE = ["--mesh", "mesh.obj", "--repeats", "2", "2"]
SMALL = ["--mesh", "plane", "--mesh-res", "2", "--repeats", "2", "2"]
RENDER = ["render", "-q", *SMALL, "--width", "16", "--height", "12", "--spp", "1"]


def cases():
    """(name, argv, expect): expect 'refuse' (must exit non-zero) or 'any' (either, judged by its output)."""
    c = []
    add = lambda name, argv, expect="refuse", out=None: c.append((name, argv, expect, out))
    # --- absurd numbers per numeric flag of the scene commands
    nums = ["0", "-1", "1e308", "-1e308", "nan", "inf", "-inf", "1e-320", "99999999999999999999", "0x10", ""]
    scene_flags = ["--ply-pitch", "--ply-radius", "--ply-center-radius", "--samples-per-turn", "--clamp-tolerance",
                   "--weld-tolerance", "--plies", "--mesh-res"]
    for flag in scene_flags:
        for v in nums:
            base = ["build", "-q", *SMALL, "-o", "o.obj"] if flag != "--mesh-res" else \
                ["build", "-q", "--mesh", "plane", "--repeats", "2", "2", "-o", "o.obj"]
            add(f"build {flag} {v or '(empty)'}", [*base, flag, v], "any", "o.obj")
    for v in nums + ["1e9 1e9", "0 5", "-2 2", "nan 1"]:
        add(f"build --repeats {v or '(empty)'}", ["build", "-q", "--mesh", "plane", "--mesh-res", "2", "--repeats",
                                                   *(v.split() if " " in v else [v, v]), "-o", "o.obj"], "any", "o.obj")
    for g in ["0x0/10cm", "22x30/0cm", "22x30/-1cm", "nanxnan/10cm", "1e308x1e308/1mm", "22x30", "22x30/10parsec",
              "x/", "1e-300x1e-300/1m", "22x30/10cm/3"]:
        add(f"build --gauge {g}", ["build", "-q", "--mesh", "plane", "--mesh-res", "2", "--gauge", g, "-o", "o.obj"],
            "any", "o.obj")
    for m in ["0", "-1G", "1e308G", "nanG", "1T", "1", "5X", "", "0.0001K"]:
        add(f"build --max-memory {m or '(empty)'}", ["build", "-q", *SMALL, "--max-memory", m, "-o", "o.obj"],
            "any", "o.obj")
    add("build --twist X", ["build", "-q", *SMALL, "--twist", "X", "-o", "o.obj"])
    add("build --export tubes --sides 2", ["build", "-q", *SMALL, "--export", "tubes", "--sides", "2", "-o", "o.glb"])
    add("build --chunk-vertices 1", ["build", "-q", *SMALL, "--export", "tubes", "--chunk-vertices", "1", "-o",
                                     "o.glb"], "any", "o.glb")
    add("build --chunk-vertices 2", ["build", "-q", *SMALL, "--chunk-vertices", "2", "-o", "o.glb"], "any", "o.glb")
    add("build --bake-size 0", ["build", "-q", *SMALL, "--surface-only", "--bake-size", "0", "-o", "o.glb"])
    add("build --bake-size 1e9", ["build", "-q", *SMALL, "--surface-only", "--bake-size", "1000000000", "-o",
                                  "o.glb"])
    add("build --surface-only -o o.obj", ["build", "-q", *SMALL, "--surface-only", "-o", "o.obj"])
    add("build --detail view without camera", ["build", "-q", *SMALL, "--detail", "view", "-o", "o.obj"], "any",
        "o.obj")
    add("build --detail view --width 0", ["build", "-q", *SMALL, "--detail", "view", "--width", "0", "-o", "o.obj"])
    add("build --detail view --fov 180", ["build", "-q", *SMALL, "--detail", "view", "--fov", "180", "-o", "o.obj"])
    add("build --detail view --fov nan", ["build", "-q", *SMALL, "--detail", "view", "--fov", "nan", "-o", "o.obj"])
    add("build --eye = --target", ["build", "-q", *SMALL, "--detail", "view", "--eye", "1", "1", "1", "--target",
                                   "1", "1", "1", "-o", "o.obj"])
    add("build --up parallel to view", ["build", "-q", *SMALL, "--detail", "view", "--eye", "0", "1", "0",
                                        "--target", "0", "0", "0", "--up", "0", "1", "0", "-o", "o.obj"], "any",
        "o.obj")
    add("build --ply-pixels -1", ["build", "-q", *SMALL, "--detail", "view", "--ply-pixels", "-1", "-o", "o.obj"])
    add("build --yarn-pixels nan", ["build", "-q", *SMALL, "--detail", "view", "--yarn-pixels", "nan", "-o",
                                    "o.obj"])
    add("build --ply-pixels 1e308", ["build", "-q", *SMALL, "--detail", "view", "--ply-pixels", "1e308", "-o",
                                     "o.obj"], "any", "o.obj")
    add("build --rest other topology", ["build", "-q", "--mesh", "mesh.obj", "--rest", "badframes/f_0002.obj",
                                        "--repeats", "2", "2", "-o", "o.obj"])
    add("build --rest itself as -o", ["build", "-q", "--mesh", "mesh.obj", "--rest", "mesh.obj", "--repeats", "2",
                                      "2", "-o", "mesh.obj"])
    add("build --strain-table garbage", ["build", "-q", *SMALL, "--strain-table", "garbage.npy", "-o", "o.obj"])
    add("build --deform strain --strain-table empty", ["build", "-q", *SMALL, "--deform", "strain",
                                                       "--strain-table", "empty.npy", "-o", "o.obj"])
    add("build --deform none --strain-table x", ["build", "-q", *SMALL, "--deform", "none", "--strain-table",
                                                 "garbage.npy", "-o", "o.obj"], "any", "o.obj")
    # --- every input format: empty, truncated, garbage, a folder, missing
    for ext in ["pyp", "json"]:
        for kind in ["empty", "half", "garbage", "dir", "missing"]:
            add(f"build --pattern {kind}.{ext}", ["build", "-q", "--pattern", f"{kind}.{ext}", *SMALL[:4], "-o",
                                                 "o.obj"], "any" if kind == "half" else "refuse", "o.obj")
    for ext in ["obj", "ply", "off", "glb", "gltf"]:
        for kind in ["empty", "half", "garbage", "dir", "missing"]:
            add(f"build --mesh {kind}.{ext}", ["build", "-q", "--mesh", f"{kind}.{ext}", "--repeats", "2", "2", "-o",
                                              "o.obj"], "any" if kind == "half" else "refuse", "o.obj")
    for name in ["huge.obj", "tiny.obj", "flat_uv.obj", "no_uv.obj", "no_faces.obj", "uv_huge.obj", "neg_index.obj",
                 "zero_index.obj"]:
        add(f"build --mesh {name}", ["build", "-q", "--mesh", name, "--repeats", "2", "2", "-o", "o.obj"], "any",
            "o.obj")
        add(f"build --mesh {name} (physical)", ["build", "-q", "--mesh", name, "-o", "o.obj"], "any", "o.obj")
    # --- outputs
    for out in ["", "dir.obj", "missing/o.obj", "ro/o.obj", "ro.txt/o.obj", "o.xyz", "o", ".obj", "/dev/null",
                "o.OBJ", "mesh.obj", "good.pyp"]:
        add(f"build -o {out or '(empty)'}", ["build", "-q", *SCENE, "--pattern", "good.pyp", "-o", out], "any",
            out if out and out != "/dev/null" else None)
    add("build -o a 244-byte name", ["build", "-q", *SMALL, "-o", "a" * 240 + ".obj"], "any", "a" * 240 + ".obj")
    add("animate -o a 244-byte name", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o",
                                       "a" * 240 + ".pc2"], "any", "a" * 240 + ".pc2")
    add("build -o a 304-byte name", ["build", "-q", *SMALL, "-o", "b" * 300 + ".obj"])
    add("build --report dir", ["build", "-q", *SMALL, "-o", "o.obj", "--report", "dir.obj"])
    add("build --report = -o", ["build", "-q", *SMALL, "-o", "o.obj", "--report", "o.obj"])
    add("build -o .gltf beside .bin named as report", ["build", "-q", *SMALL, "-o", "o.gltf", "--report", "o.bin"])
    add("build --draco --quantize", ["build", "-q", *SMALL, "--draco", "--quantize", "-o", "o.glb"])
    add("build --draco -o o.obj", ["build", "-q", *SMALL, "--export", "tubes", "--draco", "-o", "o.obj"])
    add("build --quantize curves", ["build", "-q", *SMALL, "--quantize", "-o", "o.glb"], "any", "o.glb")
    add("build --yarn-colors -o o.obj", ["build", "-q", *SMALL, "--yarn-colors", "-o", "o.obj"], "any", "o.obj")
    add("build --tubes-of plies --export yarns", ["build", "-q", *SMALL, "--tubes-of", "plies", "--export", "yarns",
                                                  "-o", "o.obj"], "any", "o.obj")
    add("build unknown flag", ["build", "--no-such-flag"])
    add("build positional", ["build", "extra"])
    # --- chart
    for arg in ["empty.chart", "half.chart", "garbage.chart", "dir.chart", "missing.chart", "chart:", "chart:nope",
                "chart:../../etc/passwd"]:
        add(f"chart {arg}", ["chart", arg, "-o", "c.pyp"], "any" if arg == "half.chart" else "refuse", "c.pyp")
    for v in ["0", "-1", "nan", "inf", "1e308", "1e-300"]:
        add(f"chart --yarn-radius {v}", ["chart", "good.chart", "--yarn-radius", v, "-o", "c.pyp"], "any", "c.pyp")
    add("chart -o = chart", ["chart", "good.chart", "-o", "good.chart"])
    add("chart -o dir", ["chart", "good.chart", "-o", "dir.pyp"])
    add("chart --max-float 0", ["chart", "good.chart", "--max-float", "0", "-o", "c.pyp"])
    write_chart = ("wide.chart", "k" * 20000 + "\n")
    add("chart one row 20000 wide", ["chart", "wide.chart", "-o", "c.pyp"], "any", "c.pyp")
    add("chart 3000 rows", ["chart", "tall.chart", "-o", "c.pyp"], "any", "c.pyp")
    # --- generate
    for flag in ["--a", "--h", "--d", "--row-gap", "--model-radius", "--radius", "--samples"]:
        for v in ["0", "-1", "nan", "inf", "1e308", "1e-308"]:
            add(f"generate {flag} {v}", ["generate", flag, v, "-o", "g.pyp"], "any", "g.pyp")
    add("generate unknown name", ["generate", "garter", "-o", "g.pyp"])
    add("generate -o dir", ["generate", "-o", "dir.pyp"])
    # --- info
    for arg in ["empty.pyp", "garbage.pyp", "dir.pyp", "missing.pyp", "garbage.npy", "empty.npy", "dir.npy",
                "good.knitbind", "mesh.obj", "/dev/zero", "half.json"]:
        add(f"info {arg}", ["info", arg])
    # --- bind / animate
    add("bind -o dir", ["bind", "-q", *SCENE, "-o", "dir.knitbind"])
    add("bind -o = mesh", ["bind", "-q", *SCENE, "-o", "mesh.obj"])
    for kind in ["empty", "half", "garbage", "dir", "missing"]:
        add(f"animate --bound {kind}.knitbind", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--bound",
                                                 f"{kind}.knitbind", "-o", "a.pc2"])
        add(f"render --bound {kind}.knitbind", ["render", "-q", "--bound", f"{kind}.knitbind", "--width", "8",
                                                "--height", "8", "--spp", "1", "--output", "r.png"])
    for frames in ["frames/f_%d%d.obj", "frames/f_%s.obj", "frames/f_%n.obj", "frames/f_%99999999d.obj",
                   "frames/f_%04d.obj%", "emptyframes", "missing/f_%04d.obj", "badframes/f_%04d.obj",
                   "nanframes/f_%04d.obj", "garbage.glb", "mesh.obj", "frames"]:
        add(f"animate --frames {frames}", ["animate", "-q", "--frames", frames, "--repeats", "2", "2", "-o", "a.pc2"],
            "any", "a.pc2")
    for flag, v in [("--first", "5"), ("--last", "-5"), ("--step", "0"), ("--step", "-1"),
                    ("--step", "99999999999"), ("--first", "-2147483648"), ("--fps", "0"), ("--fps", "nan"),
                    ("--fps", "-24"), ("--fps", "1e308"), ("--fps", "1e-308"), ("--threads", "-1")]:
        add(f"animate {flag} {v}", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", flag, v,
                                    "-o", "a.pc2"], "any", "a.pc2")
    add("animate --fps 0 mdd", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "--fps",
                                "0", "-o", "a.mdd"], "any", "a.mdd")
    add("animate -o = frame", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o",
                               "frames/f_0001.obj"])
    add("animate -o pattern = frames", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2",
                                        "-o", "frames/f_%04d.obj"])
    add("animate -o a.pc2 topology = rest", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--rest", "a.obj",
                                             "--repeats", "2", "2", "-o", "a.pc2"])
    add("animate -o a.xyz", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o", "a.xyz"])
    add("animate -o a_%d_%d.obj", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o",
                                   "a_%d_%d.obj"])
    add("animate -o a_%s.obj", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2", "-o",
                                "a_%s.obj"])
    add("animate --rest other topology", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--rest",
                                          "badframes/f_0002.obj", "--repeats", "2", "2", "-o", "a.pc2"])
    # --- cache merge
    for args in [["good.pc2", "good.pc2"], ["empty.pc2"], ["half.pc2"], ["garbage.pc2"], ["dir.pc2"], ["missing.pc2"],
                 ["good.pc2", "dup.pc2"]]:
        add(f"cache merge {' '.join(args)}", ["cache", "merge", *args, "-o", "m.pc2"], "any", "m.pc2")
    add("cache merge -o = chunk", ["cache", "merge", "good.pc2", "-o", "good.pc2"])
    add("cache merge no chunk", ["cache", "merge", "-o", "m.pc2"])
    # --- render
    for flag, vals in [("--width", ["0", "-1", "99999999999", "1e9"]), ("--height", ["0", "-5"]),
                       ("--spp", ["0", "-1", "2147483647"]), ("--fov", ["0", "180", "-10", "nan", "1e308"]),
                       ("--max-depth", ["-1", "0", "1000000000"]), ("--env", ["nan", "-1", "1e308", "inf"]),
                       ("--light-irradiance", ["nan", "-1", "inf"]), ("--eta", ["0", "nan", "-1", "1e308"]),
                       ("--alpha-along", ["0", "-1", "nan"]), ("--kR", ["nan", "2", "-1", "1,2", "a,b,c"]),
                       ("--body-albedo", ["1.5", "nan"]), ("--tube-sides", ["0", "2", "1000000000"]),
                       ("--scattering-paths", ["-1", "1e9", "nan"]), ("--fiber-count", ["0", "-1", "1e308"]),
                       ("--seed", ["-1"]), ("--bake-size", ["0", "100000000"])]:
        for v in vals:
            extra = ["--mode", "tubes"] if flag == "--tube-sides" else []
            add(f"render {flag} {v}", [*RENDER, *extra, flag, v, "--output", "r.png"], "any", "r.png")
    add("render --eye = --target", [*RENDER, "--eye", "1", "1", "1", "--target", "1", "1", "1", "--output", "r.png"])
    add("render --eye nan", [*RENDER, "--eye", "nan", "1", "1", "--target", "0", "0", "0", "--output", "r.png"])
    add("render --eye 1e308", [*RENDER, "--eye", "1e308", "1", "1", "--target", "0", "0", "0", "--output", "r.png"],
        "any", "r.png")
    add("render --up 0 0 0", [*RENDER, "--eye", "0", "0", "2", "--target", "0", "0", "0", "--up", "0", "0", "0",
                              "--output", "r.png"])
    add("render no output (prints its report)", [*RENDER], "any")
    add("render --output dir", [*RENDER, "--output", "dir.png"])
    if os.geteuid() != 0:  # root writes into a read-only folder
        add("render --output ro/r.png", [*RENDER, "--output", "ro/r.png"])
    add("render --exr = --output", [*RENDER, "--output", "r.png", "--exr", "r.png"])
    for m in ["missing.json", "dir.json", "empty.json", "garbage.json", "mat_nan.json", "mat_bad.json",
              "mat_huge.json", "mat_list.json", "/dev/zero"]:
        add(f"render --material {m}", [*RENDER, "--material", m, "--output", "r.png"])
    add("render --frame-mesh without --bound", [*RENDER, "--frame-mesh", "mesh.obj", "--output", "r.png"])
    add("render --bound --frame-mesh other topology", ["render", "-q", "--bound", "good.knitbind", "--frame-mesh",
                                                       "badframes/f_0002.obj", "--width", "8", "--height", "8",
                                                       "--spp", "1", "--output", "r.png"])
    add("render --bound --frame-mesh nan", ["render", "-q", "--bound", "good.knitbind", "--frame-mesh",
                                            "nanframes/f_0002.obj", "--width", "8", "--height", "8", "--spp", "1",
                                            "--output", "r.png"])
    # --- fit
    FIT = ["fit", "-q", *SMALL, "--spp", "1", "--max-evaluations", "2", "--budget", "20"]
    for front, back in [("empty.png", "photo.png"), ("garbage.png", "photo.png"), ("half.png", "photo.png"),
                        ("dir.png", "photo.png"), ("missing.png", "photo.png"), ("photo.png", "garbage.exr"),
                        ("photo.png", "half.exr"), ("photo.png", "mesh.obj"), ("photo.png", "photo.png")]:
        add(f"fit --front {front} --back {back}", [*FIT, "--front", front, "--back", back, "-o", "f.json"], "any",
            "f.json")
    for args in [["--fit", "nope"], ["--fit", ""], ["--bound", "kR=1:0"], ["--bound", "kR=nan:1"], ["--bound", "x"],
                 ["--budget", "0"], ["--budget", "-1"], ["--budget", "nan"], ["--max-evaluations", "0"],
                 ["--max-evaluations", "-1"], ["--mask", "garbage.png"], ["--mask", "missing.png"]]:
        add(f"fit {' '.join(args)}", [*FIT, "--front", "photo.png", "--back", "photo.png", *args, "-o", "f.json"],
            "any", "f.json")
    add("fit -o = --front", [*FIT, "--front", "photo.png", "--back", "photo.png", "-o", "photo.png"])
    # --- strain-table
    ST = ["strain-table", "-q", "--samples", "2", "2", "2", "--iterations", "5"]
    for args in [["--samples", "0", "1", "1"], ["--samples", "-1", "2", "2"], ["--samples", "100000", "100000",
                                                                                  "100000"],
                 ["--sx-range", "1", "0"], ["--sx-range", "nan", "1"], ["--sa-range", "-1e308", "1e308"],
                 ["--sy-range", "-5", "-2"], ["--sx-range", "0", "0"], ["--iterations", "0"]]:
        add(f"strain-table {' '.join(args)}", [*ST, *args, "-o", "t.npy"], "any", "t.npy")
    add("strain-table -o dir", [*ST, "-o", "dir.npy"])
    add("strain-table -o t.txt", [*ST, "-o", "t.txt"], "any", "t.txt")
    add("strain-table -o good.pyp", [*ST, "--pattern", "good.pyp", "-o", "good.pyp"])
    add("strain-table --pattern garbage", [*ST, "--pattern", "garbage.pyp", "-o", "t.npy"])
    # --- serve
    for args in [["--port", "-1"], ["--port", "70000"], ["--host", "not a host"], ["--host", "8.8.8.8"],
                 ["--jobs", "0"], ["--max-upload-mb", "nan"], ["--max-memory", "-1G"]]:
        add(f"serve {' '.join(args)}", ["serve", *args])
    # --- top level
    add("no subcommand", [])
    add("unknown subcommand", ["views"])
    add("cache without merge", ["cache"])
    return c


def fresh_cases():
    """Round 4 of the hunt (issue 29): the flags and formats rounds 1-3 did not try."""
    c = []
    add = lambda name, argv, expect="refuse", out=None: c.append((name, argv, expect, out))
    # --- concave faces, degenerate UVs, absurd sizes and odd names per mesh format
    for name in ["concave.obj", "concave.off", "concave.ply", "concave_bin.ply", "uv_nan.obj", "uv_zero.ply",
                 "huge.off", "tiny.ply", "mesh.stl", "mesh.OBJ", "crlf.obj", "big_face.obj", "ply_count.ply"]:
        add(f"build --mesh {name}", ["build", "-q", "--mesh", name, "--repeats", "2", "2", "-o", "o.obj"], "any",
            "o.obj")
    add("build --mesh huge.off (physical)", ["build", "-q", "--mesh", "huge.off", "-o", "o.obj"], "any", "o.obj")
    add("build --mesh tiny.ply (physical)", ["build", "-q", "--mesh", "tiny.ply", "-o", "o.obj"], "any", "o.obj")
    add("build --mesh concave.ply --rest concave.off", ["build", "-q", "--mesh", "concave.ply", "--rest",
                                                        "concave.off", "--repeats", "2", "2", "-o", "o.obj"],
        "any", "o.obj")
    # --- curves JSON patterns with absurd content
    for name in ["c_period0", "c_periodneg", "c_period_huge", "c_radius0", "c_nocurves", "c_onepoint", "c_2d",
                 "c_far", "c_string", "c_deep", "c_big_number"]:
        add(f"build --pattern {name}.json", ["build", "-q", "--pattern", f"{name}.json", *SMALL[:4], "--repeats",
                                             "2", "2", "-o", "o.obj"], "any", "o.obj")
    # --- export flags rounds 1-3 never set
    for args in [["--draco", "--draco-bits", "1"], ["--draco", "--draco-bits", "30"], ["--draco", "--draco-bits", "0"],
                 ["--draco", "--draco-level", "11"], ["--draco", "--draco-level", "-1"], ["--meshopt"],
                 ["--meshopt", "--quantize"], ["--meshopt", "--draco"], ["--draco-bits", "12"], ["--no-caps"],
                 ["--sides", "1024"], ["--sides", "1025"], ["--pretty-json"], ["--yarn-colors", "--draco"],
                 ["--chunk-vertices", "2147483649"]]:
        add(f"build --export tubes {' '.join(args)}", ["build", "-q", *SMALL, "--export", "tubes", *args, "-o",
                                                       "o.glb"], "any", "o.glb")
    for v in ["1e-7", "1e-6", "1e-5"]:
        add(f"build --export plies --ply-pitch {v}", ["build", "-q", *SMALL, "--export", "plies", "--ply-pitch", v,
                                                      "-o", "o.glb"], "any", "o.glb")
        add(f"build --export tubes --ply-pitch {v} --draco", ["build", "-q", *SMALL, "--export", "tubes",
                                                              "--ply-pitch", v, "--draco", "-o", "o.glb"], "any",
            "o.glb")
    add("build --samples-per-turn 1e6 --export tubes --sides 1024", ["build", "-q", *SMALL, "--export", "tubes",
                                                                     "--samples-per-turn", "1000000", "--sides",
                                                                     "1024", "-o", "o.glb"], "any", "o.glb")
    add("build --export TUBES (any case)", ["build", "-q", *SMALL, "--export", "TUBES", "-o", "o.glb"], "any",
        "o.glb")
    add("build --export nothing", ["build", "-q", *SMALL, "--export", "nothing", "-o", "o.glb"])
    add("build --tubes-of nothing", ["build", "-q", *SMALL, "--tubes-of", "nothing", "-o", "o.glb"])
    add("build --deform nothing", ["build", "-q", *SMALL, "--deform", "nothing", "-o", "o.obj"])
    add("build --detail nothing", ["build", "-q", *SMALL, "--detail", "nothing", "-o", "o.obj"])
    # --- duplicate and conflicting flags
    add("build --repeats twice", ["build", "-q", *SMALL, "--repeats", "3", "3", "-o", "o.obj"], "any", "o.obj")
    add("build -o twice", ["build", "-q", *SMALL, "-o", "a.obj", "-o", "b.obj"], "any")
    add("build --mesh twice", ["build", "-q", "--mesh", "plane", "--mesh", "mesh.obj", "--repeats", "2", "2", "-o",
                               "o.obj"], "any")
    add("build --gauge with --repeats", ["build", "-q", *SMALL, "--gauge", "22x30/10cm", "-o", "o.obj"], "any",
        "o.obj")
    add("build --report = --pattern", ["build", "-q", *SMALL, "--pattern", "good.pyp", "-o", "o.obj", "--report",
                                       "good.pyp"])
    add("build --report = --mesh", ["build", "-q", "--mesh", "mesh.obj", "--repeats", "2", "2", "-o", "o.obj",
                                    "--report", "mesh.obj"])
    add("build --strain-table = -o", ["build", "-q", *SMALL, "--deform", "strain", "--strain-table", "o.npy", "-o",
                                      "o.npy"])
    add("build --mesh-res 100000", ["build", "-q", "--mesh", "plane", "--mesh-res", "100000", "--repeats", "1", "1",
                                    "-o", "o.obj"])
    add("build --mesh-res 1 --repeats 1e7 1e7", ["build", "-q", "--mesh", "plane", "--mesh-res", "1", "--repeats",
                                                 "1e7", "1e7", "-o", "o.obj"])
    add("build --threads 100000", ["build", "-q", *SMALL, "--threads", "100000", "-o", "o.obj"], "any", "o.obj")
    # --- chart: odd bytes, odd names
    for name in ["nul", "crlf", "tabs", "blank", "utf", "one"]:
        add(f"chart {name}.chart", ["chart", f"{name}.chart", "-o", "c.pyp"], "any", "c.pyp")
    add("chart -o c.obj (not a pattern)", ["chart", "good.chart", "-o", "c.obj"], "refuse", "c.obj")
    add("chart --report = chart", ["chart", "good.chart", "-o", "c.pyp", "--report", "good.chart"])
    add("chart --max-float -1", ["chart", "good.chart", "--max-float", "-1", "-o", "c.pyp"])
    add("chart --max-float 1e9", ["chart", "good.chart", "--max-float", "1000000000", "-o", "c.pyp"], "any", "c.pyp")
    # --- generate: each flag within range, their combination outside any knit
    for args in [["--h", "0.4", "--row-gap", "-0.39"], ["--model-radius", "3", "--a", "3"], ["--d", "6", "--h", "0.4"],
                 ["--samples", "4", "--a", "-3.1"], ["--samples", "1000000000"], ["--k", "1"], ["--samples", "3.5"],
                 ["--max-memory", "1K"]]:
        add(f"generate {' '.join(args)}", ["generate", *args, "-o", "g.pyp"], "any", "g.pyp")
    add("generate -o g.obj", ["generate", "-o", "g.obj"], "refuse", "g.obj")
    add("generate -o = an input", ["generate", "-o", "good.pyp"], "any", "good.pyp")
    # --- info on the formats rounds 1-3 did not try
    for arg in ["good.pc2", "good.mdd", "good.chart", "curves.json", "tube.glb", "huge_count.pc2", "c_deep.json",
                "concave.ply", "nul.chart", "photo.exr"]:
        add(f"info {arg}", ["info", arg], "any")
    # --- caches: absurd headers, MDD, mixed formats
    for args in [["huge_count.pc2"], ["neg_frames.pc2"], ["nan_fps.pc2"], ["nan_frame.pc2"], ["huge_count.mdd"],
                 ["empty.mdd"], ["garbage.mdd"], ["good.pc2", "good.mdd"], ["good.mdd", "good.mdd"],
                 ["good.mdd", "nan_frame.pc2"]]:
        add(f"cache merge {' '.join(args)} -o m.pc2", ["cache", "merge", *args, "-o", "m.pc2"], "any", "m.pc2")
    add("cache merge -o m.mdd from pc2", ["cache", "merge", "good.pc2", "-o", "m.mdd"], "any", "m.mdd")
    add("cache merge -o m.obj", ["cache", "merge", "good.pc2", "-o", "m.obj"])
    add("cache merge -o = topology", ["cache", "merge", "good.pc2", "-o", "good.obj"])
    # --- animate: frames of other formats and odd numbers
    add("animate --frames concave faces (ply)", ["animate", "-q", "--frames", "concave.ply", "--repeats", "2", "2",
                                                 "-o", "a.pc2"], "any", "a.pc2")
    add("animate --threads 0", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2",
                                "--threads", "0", "-o", "a.pc2"], "any", "a.pc2")
    add("animate -o a.glb --draco", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2",
                                     "--draco", "-o", "a.glb"], "any", "a.glb")
    add("animate --bound good --repeats 3 3", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--bound",
                                                "good.knitbind", "--repeats", "3", "3", "-o", "a.pc2"], "any", "a.pc2")
    add("animate --bound good -o = bound", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--bound",
                                            "good.knitbind", "-o", "good.knitbind"])
    add("animate --step 2147483647", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2",
                                      "--step", "2147483647", "-o", "a.pc2"], "any", "a.pc2")
    add("animate --first 2147483647", ["animate", "-q", "--frames", "frames/f_%04d.obj", "--repeats", "2", "2",
                                       "--first", "2147483647", "-o", "a.pc2"], "any", "a.pc2")
    # --- bind
    add("bind --mesh concave.off", ["bind", "-q", "--mesh", "concave.off", "--repeats", "2", "2", "-o", "b.knitbind"],
        "any", "b.knitbind")
    add("bind -o b.obj", ["bind", "-q", *SCENE, "-o", "b.obj"], "refuse", "b.obj")
    add("bind --mesh huge.off (physical)", ["bind", "-q", "--mesh", "huge.off", "-o", "b.knitbind"], "any",
        "b.knitbind")
    # --- render: flags rounds 1-3 never set, extreme scenes
    for flag, vals in [("--alpha-across", ["nan", "-1", "1e308"]), ("--alpha-tt", ["nan", "0", "inf"]),
                       ("--reflect-fraction", ["nan", "-0.5", "2"]), ("--fiber-twist", ["nan", "1e308"]),
                       ("--fiber-shadow-floor", ["nan", "-1", "2"]), ("--ply-shadow-floor", ["nan", "5"]),
                       ("--light", ["nope", ""]), ("--mode", ["nope"]), ("--seed", ["1e30", "nan"]),
                       ("--max-depth", ["nan"]), ("--threads", ["0", "-5"])]:
        for v in vals:
            add(f"render {flag} {v or '(empty)'}", [*RENDER, flag, v, "--output", "r.png"], "any", "r.png")
    add("render --base-mesh --mesh concave.ply", ["render", "-q", "--mesh", "concave.ply", "--repeats", "2", "2",
                                                  "--width", "16", "--height", "12", "--spp", "1", "--base-mesh",
                                                  "--output", "r.png"], "any", "r.png")
    add("render --mesh huge.off (physical)", ["render", "-q", "--mesh", "huge.off", "--width", "16", "--height", "12",
                                              "--spp", "1", "--output", "r.png"], "any", "r.png")
    add("render --mesh huge.obj --repeats 2 2", ["render", "-q", "--mesh", "huge.obj", "--repeats", "2", "2",
                                                 "--width", "16", "--height", "12", "--spp", "1", "--output",
                                                 "r.png"], "any", "r.png")
    add("render --mode tubes --mesh tiny.obj", ["render", "-q", "--mesh", "tiny.obj", "--repeats", "2", "2", "--mode",
                                                "tubes", "--width", "16", "--height", "12", "--spp", "1", "--output",
                                                "r.png"], "any", "r.png")
    add("render --output r.PNG", [*RENDER, "--output", "r.PNG"], "any", "r.PNG")
    add("render --output = --mesh", ["render", "-q", "--mesh", "photo.png", "--repeats", "2", "2", "--output",
                                     "photo.png"])
    add("render --exr r.exr (no --output)", [*RENDER, "--exr", "r.exr"], "any", "r.exr")
    add("render --exr dir", [*RENDER, "--output", "r.png", "--exr", "dir.exr"])
    add("render --report = --exr", [*RENDER, "--output", "r.png", "--exr", "r.exr", "--report", "r.exr"])
    add("render --width 65536 --height 65536", [*RENDER[:-6], "--width", "65536", "--height", "65536", "--spp", "1",
                                                "--output", "r.png"])
    # --- fit
    FIT = ["fit", "-q", *SMALL, "--spp", "1", "--max-evaluations", "2", "--budget", "20"]
    add("fit --front 1x1 image", [*FIT, "--front", "tiny.png", "--back", "photo.png", "-o", "f.json"], "any", "f.json")
    add("fit --fit kR --bound kR=0:1e308", [*FIT, "--front", "photo.png", "--back", "photo.png", "--fit", "kR",
                                            "--bound", "kR=0:1e308", "-o", "f.json"], "any", "f.json")
    add("fit -o f.png", [*FIT, "--front", "photo.png", "--back", "photo.png", "-o", "f.png"], "refuse", "f.png")
    add("fit --mask other size", [*FIT, "--front", "photo.png", "--back", "photo.png", "--mask", "tiny.png", "-o",
                                  "f.json"], "any", "f.json")
    # --- strain-table
    ST = ["strain-table", "-q", "--samples", "2", "2", "2", "--iterations", "5"]
    for args in [["--iterations", "1000000000"], ["--samples", "2", "2", "2", "2"], ["--sx-range", "0.5", "1e308"],
                 ["--pattern", "concave.obj"], ["--pattern", "curves.json"], ["--max-memory", "1K"],
                 ["--sy-range", "inf", "inf"]]:
        add(f"strain-table {' '.join(args)}", [*ST, *args, "-o", "t.npy"], "any", "t.npy")
    add("strain-table -o t.NPY", [*ST, "-o", "t.NPY"], "any", "t.NPY")
    add("build --deform strain --strain-table of another pattern", ["build", "-q", "--pattern", "curves.json",
                                                                     *SMALL[:4], "--repeats", "2", "2", "--deform",
                                                                     "strain", "--strain-table", "t.npy", "-o",
                                                                     "o.obj"], "any", "o.obj")
    # --- serve
    for args in [["--port", "0", "--jobs", "1000000000"], ["--max-result-mb", "0"], ["--host", ""],
                 ["--port", "nan"]]:
        add(f"serve {' '.join(args)}", ["serve", *args])
    return c


def snapshot(root):
    files = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for n in filenames + [d for d in dirnames]:
            p = os.path.join(dirpath, n)
            rel = os.path.relpath(p, root)
            if os.path.isdir(p) and not os.path.islink(p):
                files[rel + "/"] = ""
            else:
                try:
                    files[rel] = hashlib.sha1(open(p, "rb").read()).hexdigest()
                except OSError:
                    files[rel] = "?"
    return files


def judge(rc, out, err, peak, new, changed, expect, output, folder):
    why = []
    if rc is None:
        why.append("hang (timeout)")
    elif rc < 0 or rc >= 128:
        why.append(f"signal/abort (exit {rc})")
    elif rc == 3:
        why.append("internal error (exit 3)")
    if peak > 2 * GB:
        why.append(f"peak RSS {peak / GB:.1f} GB")
    text = err + out
    for pat in FOREIGN:
        if re.search(pat, text):
            why.append(f"names another front end's spelling /{pat}/")
    for pat in INTERNAL:
        if re.search(pat, err):
            why.append(f"names an internal /{pat}/")
    for pat, what in MISLEADING:
        if re.search(pat, err):
            why.append(what)
    if changed:
        why.append("changed inputs " + ",".join(changed))
    temps = [f for f in new if ".tmp" in f or ".knit-staging" in f]
    if temps:
        why.append("temporary left " + ",".join(temps))
    if rc not in (0, None) and rc < 128:
        left = [f for f in new if f not in temps]
        if left:
            why.append("refused but left " + ",".join(left))
        if rc == 1 and "knit: error:" not in err:
            why.append("exit 1 without 'knit: error:'")
        if not err.strip():
            why.append("refused without a message")
    if rc == 0:
        if re.search(r":\s*\[?\s*null", out):  # a JSON report (render prints one) with a non-finite number
            why.append("exit 0 with null (non-finite) in the printed report")
        if expect == "refuse":
            why.append("accepted (exit 0), expected a refusal")
        if output:
            p = os.path.join(folder, output)
            if os.path.isfile(p):
                data = open(p, "rb").read()
                if not data:
                    why.append("exit 0 with an empty output")
                elif output.endswith((".obj", ".pyp", ".json", ".ply")):
                    head = data[:4_000_000].decode("latin-1")
                    if re.search(r"(?i)(?<![a-z])(nan|-?inf)(?![a-z])", head):
                        why.append("exit 0 with nan/inf in the output")
            elif not output.startswith("/") and "%" not in output and not os.path.isdir(p):
                why.append(f"exit 0 but no {output}")
    return why


def run_case(knit, fixtures, timeout, case):
    name, argv, expect, output = case
    folder = tempfile.mkdtemp(prefix="hostile-")
    shutil.rmtree(folder)
    shutil.copytree(fixtures, folder, symlinks=True)
    os.chmod(os.path.join(folder, "ro"), 0o555)
    if "wide.chart" in argv:
        write(os.path.join(folder, "wide.chart"), "k" * 20000 + "\n")
    if "tall.chart" in argv:
        write(os.path.join(folder, "tall.chart"), "k k\n" * 3000)
    before = snapshot(folder)
    timefile = os.path.join(tempfile.gettempdir(), f"hostile-time-{os.getpid()}.txt")
    # An address-space cap (8 GiB) keeps a runaway allocation from taking the machine: it ends in
    # an allocation failure (exit 3, mishandled) instead, and the peak is still measured.
    cmd = ["/usr/bin/time", "-v", "-o", timefile, "prlimit", f"--as={8 * GB}", "timeout", "-s", "KILL", str(timeout),
           knit, *argv]
    try:
        p = subprocess.run(cmd, cwd=folder, capture_output=True, text=True, errors="replace", timeout=timeout + 30,
                           stdin=subprocess.DEVNULL)
        rc = p.returncode
        out, err = p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        rc, out, err = None, "", ""
    peak = 0
    try:
        t = open(timefile).read()
        m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", t)
        peak = int(m.group(1)) * 1024 if m else 0
        if "Command terminated by signal" in t or rc == 137 or rc == 124:
            sig = re.search(r"terminated by signal (\d+)", t)
            rc = None if (sig and sig.group(1) == "9") or rc in (124, 137) else 128 + int(sig.group(1))
        os.unlink(timefile)
    except OSError:
        pass
    # /usr/bin/time prints "Command exited with non-zero status N" into its own file, not stderr.
    after = snapshot(folder)
    new = sorted(f for f in after if f not in before)
    changed = sorted(f for f in before if f in after and before[f] != after[f])
    why = judge(rc, out, err, peak, new, changed, expect, output, folder)
    os.chmod(os.path.join(folder, "ro"), 0o755)
    shutil.rmtree(folder, ignore_errors=True)
    first = (err.strip().splitlines() or [""])[0][:150]
    return rc, peak, why, first


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--knit", default=os.path.join(here, "..", "build", "apps", "knit", "knit"))
    ap.add_argument("--only", default="")
    ap.add_argument("--fresh", action="store_true", help="only the cases of round 4 (fresh_cases)")
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--verbose", action="store_true", help="also print the first line of each message")
    a = ap.parse_args()
    knit = os.path.abspath(a.knit)
    fixtures = tempfile.mkdtemp(prefix="hostile-fixtures-")
    try:
        make_fixtures(knit, fixtures)
        make_more_fixtures(fixtures)
        os.chmod(os.path.join(fixtures, "ro"), 0o755)
        todo = [c for c in (fresh_cases() if a.fresh else cases() + fresh_cases()) if a.only in c[0]]
        bad = 0
        print(f"{'case':58} {'exit':>5} {'peak MB':>8}  verdict")
        for case in todo:
            rc, peak, why, first = run_case(knit, fixtures, a.timeout, case)
            bad += bool(why)
            verdict = "ok" if not why else "MISHANDLED: " + "; ".join(why)
            print(f"{case[0][:58]:58} {'hang' if rc is None else rc:>5} {peak / 1e6:8.0f}  {verdict}", flush=True)
            if a.verbose or why:
                print(f"{'':58}   {first}", flush=True)
        print(f"\n{len(todo)} hostile inputs, {bad} mishandled")
        return 1 if bad else 0
    finally:
        shutil.rmtree(fixtures, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
