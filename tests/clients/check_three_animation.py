#!/usr/bin/env python3
"""three.js plays `knit animate -o out.glb` (issue 12): a small wave sequence is animated into one
GLB and into a PC2 cache; three_morph.mjs checks that the clip has a key per frame and that
mixing key k reproduces the cache's frame k. Exit 77 (skip) without node / three.js unless
CI=true."""
import argparse
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def write_wave_frame(path, k, n=8):
    """An n x n quad grid (0.1 m square, UVs in [0, 1]); the wave's amplitude grows with k."""
    with open(path, "w") as f:
        for j in range(n + 1):
            for i in range(n + 1):
                x, y = 0.1 * i / n, 0.1 * j / n
                f.write("v %.9g %.9g %.9g\n" % (x, y, 0.005 * (k - 1) * math.sin(20 * x + k)))
        for j in range(n + 1):
            for i in range(n + 1):
                f.write("vt %.9g %.9g\n" % (i / n, j / n))
        for j in range(n):
            for i in range(n):
                a = j * (n + 1) + i + 1
                b, c, d = a + 1, a + n + 2, a + n + 1
                f.write("f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n" % (a, a, b, b, c, c, a, a, c, c, d, d))


def skip_or_fail(message):
    ci = os.environ.get("CI", "") in ("true", "1")
    print(("FAIL (CI=true): " if ci else "SKIP: ") + message)
    sys.exit(1 if ci else 77)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--knit", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--node-modules", required=True)
    args = p.parse_args()
    node = shutil.which("node")
    if not node:
        skip_or_fail("node is not installed")
    if not os.path.isfile(os.path.join(args.node_modules, "three", "package.json")):
        skip_or_fail("three.js is not installed in %s (cmake --build <build> --target three_js)" % args.node_modules)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    for k in range(1, 6):
        write_wave_frame(os.path.join(args.work, "frame_%04d.obj" % k), k)
    common = [args.knit, "animate", "-q", "--no-stats", "--frames", "frame_%04d.obj", "--repeats", "3", "3"]
    for out in (["-o", "a.glb"], ["-o", "c.pc2"]):
        subprocess.run(common + out, check=True, cwd=args.work)
    r = subprocess.run([node, os.path.join(HERE, "three_morph.mjs"), args.node_modules, "a.glb", "c.pc2"],
                       cwd=args.work)
    return r.returncode


if __name__ == "__main__":
    sys.exit(main())
