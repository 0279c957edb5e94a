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
    run("render", "-q", "--mesh", "plane", "--mesh-res", "2", "--repeats", "2", "2", "--width", "16", "--height",
        "12", "--spp", "1", "--output", "photo.png", "--exr", "photo.exr")
    write(os.path.join(root, "good.chart"), "k k\nk k\n")
    write(os.path.join(root, "curves.json"), '{"period": [1, 1], "radius": 0.05, "curves": '
          '[{"points": [[0, 0.5, 0], [0.5, 0.5, 0.1], [1, 0.5, 0]]}]}')
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
    cmd = ["/usr/bin/time", "-v", "-o", timefile, "timeout", "-s", "KILL", str(timeout), knit, *argv]
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
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--verbose", action="store_true", help="also print the first line of each message")
    a = ap.parse_args()
    knit = os.path.abspath(a.knit)
    fixtures = tempfile.mkdtemp(prefix="hostile-fixtures-")
    try:
        make_fixtures(knit, fixtures)
        os.chmod(os.path.join(fixtures, "ro"), 0o755)
        todo = [c for c in cases() if a.only in c[0]]
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
