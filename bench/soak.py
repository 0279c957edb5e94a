#!/usr/bin/env python3
"""Soak test of long runs (issue 29): resident memory and open file descriptors must stay flat.

    /usr/bin/python3 bench/soak.py [--build build] [--frames 10000] [--evaluations 10000] [--blender-frames 1000]

1. `knit animate` over FRAMES frames of a small sequence (a 16 x 16-quad sheet, 10 distinct wave
   frames behind FRAMES symlinked names) into a PC2 cache: the process's VmRSS and open fds
   sampled from /proc every 20 ms.
2. The Python module: EVALUATIONS Scene.evaluate_plies calls (and as many Scene.evaluate) on
   alternating poses in one process: VmRSS and fds after each tenth.
3. The Blender add-on (when blender is installed): the frame handler over BLENDER_FRAMES frames of
   the animated grid the add-on tests use: VmRSS and fds after each tenth.
Prints one line per measurement and a summary; exits 1 when memory grows by more than 4 MiB
between the first tenth and the end, or the most fds open at once in the second half of the run
exceeds that of the first half (one fd comes and goes as each frame's file is read)."""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from grid_obj import grid_obj  # noqa: E402 - the tools folder first

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def rss_and_fds(pid="self"):
    rss = 0
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                rss = int(line.split()[1]) * 1024
    return rss, len(os.listdir(f"/proc/{pid}/fd"))


def write_sheet(path, phase):
    """A 0.2 m sheet of 16 x 16 quads with a wave of phase `phase` (tools/grid_obj.py)."""
    with open(path, "w") as f:
        f.write(grid_obj(16, 0.2, lambda x, y: 0.01 * math.sin(6 * x + phase)))


def verdict(name, samples):
    """samples: [(progress 0..1, rss, fds)]; flat = RSS growth after the first tenth <= 4 MiB and fds constant."""
    after = [s for s in samples if s[0] >= 0.1] or samples
    growth = after[-1][1] - after[0][1]
    fds = sorted({s[2] for s in after})
    # The fds may vary by the one file being read or written at a sample; they must not grow.
    first = max(s[2] for s in after[: len(after) // 2 or 1])
    last = max(s[2] for s in after[len(after) // 2:])
    ok = growth <= 4 << 20 and last <= first
    print(f"{name}: RSS {after[0][1] / 2**20:.1f} MiB at {after[0][0]:.0%} -> {after[-1][1] / 2**20:.1f} MiB at the end "
          f"(growth {growth / 2**20:+.2f} MiB, peak {max(s[1] for s in samples) / 2**20:.1f} MiB); open fds {fds}: "
          f"{'flat' if ok else 'NOT FLAT'}")
    return ok


def soak_animate(knit, frames, work):
    for k in range(10):
        write_sheet(os.path.join(work, f"wave_{k}.obj"), k * 0.6)
    for k in range(frames):
        os.symlink(f"wave_{k % 10}.obj", os.path.join(work, f"f_{k:05d}.obj"))
    cmd = [knit, "animate", "-q", "--no-stats", "--frames", "f_%05d.obj", "--repeats", "2", "2", "-o", "soak.pc2"]
    start = time.monotonic()
    p = subprocess.Popen(cmd, cwd=work)
    samples = []
    while p.poll() is None:
        try:
            samples.append((time.monotonic() - start, *rss_and_fds(p.pid)))
        except (FileNotFoundError, ProcessLookupError):
            break
        time.sleep(0.02)
    seconds = time.monotonic() - start
    if p.returncode != 0:
        sys.exit(f"knit animate failed ({p.returncode})")
    size = os.path.getsize(os.path.join(work, "soak.pc2"))
    print(f"animate: {frames} frames in {seconds:.1f} s, {size} bytes of PC2, {len(samples)} samples")
    return verdict("knit animate", [(t / seconds, r, f) for t, r, f in samples if r > 0])


def soak_python(build, evaluations):
    sys.path.insert(0, os.path.join(build, "python"))
    import knit
    import numpy as np
    scene = knit.build_scene("stockinette", "plane", repeats=(6, 6), res_u=16, res_v=16, build_plies=False)
    rest = np.array(scene.mesh.positions)
    poses = [rest + [0.0, 0.0, 0.01 * k] for k in range(10)]
    samples = []
    start = time.monotonic()
    for i in range(evaluations):
        scene.evaluate_plies(poses[i % 10])
        scene.evaluate(poses[i % 10])
        if (i + 1) % (evaluations // 10) == 0:
            samples.append(((i + 1) / evaluations, *rss_and_fds()))
    print(f"python: {evaluations} evaluate_plies + evaluate calls in {time.monotonic() - start:.1f} s")
    return verdict("Python evaluate loop", samples)


BLENDER_SCRIPT = r'''
import os, sys
sys.path.insert(0, os.path.join({root!r}, "blender"))
sys.path.insert(0, os.path.join({root!r}, "blender", "tests"))
import bpy, knit_blender
from addon_scene import make_animated_grid
knit_blender.register()
make_animated_grid()
bpy.ops.object.knit_apply(pattern="stockinette", repeats=(6, 6))
frames = {frames}
for f in range(frames):
    bpy.context.scene.frame_set(1 + f % 10)
    if (f + 1) % (frames // 10) == 0:
        rss = [int(l.split()[1]) * 1024 for l in open("/proc/self/status") if l.startswith("VmRSS:")][0]
        print("SOAK", (f + 1) / frames, rss, len(os.listdir("/proc/self/fd")), flush=True)
'''


def soak_blender(build, frames, work):
    script = os.path.join(work, "soak_blender.py")
    with open(script, "w") as f:
        f.write(BLENDER_SCRIPT.format(root=ROOT, frames=frames))
    env = dict(os.environ, KNIT_PYTHONPATH=os.path.join(build, "python"), PYTHONDONTWRITEBYTECODE="1")
    start = time.monotonic()
    out = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python", script],
                         env=env, capture_output=True, text=True, check=True).stdout
    samples = [(float(a), int(b), int(c)) for _, a, b, c in (l.split() for l in out.splitlines() if l.startswith("SOAK"))]
    print(f"blender: {frames} frame changes in {time.monotonic() - start:.1f} s (start-up included)")
    return verdict("Blender frame handler", samples)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--frames", type=int, default=10000)
    ap.add_argument("--evaluations", type=int, default=10000)
    ap.add_argument("--blender-frames", type=int, default=1000)
    a = ap.parse_args()
    ok = True
    with tempfile.TemporaryDirectory() as work:
        ok &= soak_animate(os.path.join(a.build, "apps", "knit", "knit"), a.frames, work)
        if a.evaluations:
            ok &= soak_python(a.build, a.evaluations)
        if a.blender_frames and subprocess.run(["which", "blender"], capture_output=True).returncode == 0:
            ok &= soak_blender(a.build, a.blender_frames, work)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
