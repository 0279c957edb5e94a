"""Per-frame time of `knit animate` against one `knit build --rest` of a frame (issue 12 target).

    /usr/bin/python3 tools/animate_timing.py [--build build] [--repeats 350] [--frames 6] [--res 32]

Writes the built-in drape (res x res quads, as `knit build --mesh drape` has it) under a
travelling wave as OBJ frames into a temporary folder, then runs, one after the other:
  * `knit animate --frames f_%04d.obj --repeats R R -o c.pc2 --report a.json` with --no-stats,
  * the same with the statistics (maxStretch, minYarnDistance) in the report,
  * `knit build --rest f_0001.obj --mesh f_0003.obj --repeats R R -o b.bcc`, the same ply points
    of one frame (BCC: the curve format nearest a raw point cache), timed around the whole process,
and prints the median frame time of each animate run (from its report: a frame's time includes
reading its mesh and writing its cache frame) over the build's wall-clock time.
Not a unit test: numbers depend on the machine and its load; run it on an idle machine.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time


def write_frames(knit, folder, res, frames):
    mesh = knit.load_mesh("drape", res, res)
    p, f = mesh.positions, mesh.faces
    uv, fuv = mesh.uvs, mesh.face_uvs
    for k in range(1, frames + 1):
        with open(os.path.join(folder, "f_%04d.obj" % k), "w") as out:
            for x, y, z in p:
                out.write("v %.9g %.9g %.9g\n" % (x, y + 0.01 * math.sin(20.0 * x + 0.2 * k), z))
            for u, v in uv:
                out.write("vt %.17g %.17g\n" % (u, v))
            for (a, b, c), (ta, tb, tc) in zip(f, fuv):
                out.write("f %d/%d %d/%d %d/%d\n" % (a + 1, ta + 1, b + 1, tb + 1, c + 1, tc + 1))


def run(cmd, cwd):
    t = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stdout))
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--repeats", type=float, default=350)
    ap.add_argument("--frames", type=int, default=6)
    ap.add_argument("--res", type=int, default=32)
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    sys.path.insert(0, os.path.join(build, "python"))
    import knit

    cli = os.path.join(build, "apps", "knit", "knit")
    rep = ["--repeats", str(a.repeats), str(a.repeats)]
    with tempfile.TemporaryDirectory() as d:
        write_frames(knit, d, a.res, a.frames)
        medians = {}
        for name, extra in (("no stats", ["--no-stats"]), ("stats", [])):
            run([cli, "animate", "-q", "--frames", "f_%04d.obj"] + rep + ["-o", "c.pc2", "--report", "a.json"] + extra, d)
            r = json.load(open(os.path.join(d, "a.json")))
            medians[name] = (r["frameSeconds"]["median"], r["stageSeconds"], r["yarnVertices"], r["plyVertices"])
        build_s = run([cli, "build", "-q", "--rest", "f_0001.obj", "--mesh", "f_0003.obj"] + rep + ["-o", "b.bcc"], d)
    for name, (median, stages, yv, pv) in medians.items():
        print("animate (%s): %d yarn / %d ply vertices, median frame %.3f s = %.3f x build --rest (%.3f s); "
              "stage totals %s" % (name, yv, pv, median, median / build_s, build_s,
                                   {k: round(v, 3) for k, v in stages.items()}))


if __name__ == "__main__":
    main()
