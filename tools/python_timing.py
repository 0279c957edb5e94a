"""Timing of the Python module and the Blender add-on's per-frame work (issue 14 targets).

    /usr/bin/python3 tools/python_timing.py [--build build] [--yarn-points 1000000]

Prints, for a drape scene scaled to ~N yarn points (and one to ~N ply points):
  * `import knit` wall time (a fresh interpreter, best of 5);
  * Scene.evaluate from Python vs the same C++ calls (the scene's yarn Animator into a fresh
    AnimationFrame) looped inside the module (knit._evaluate_seconds_in_cpp), best of 5, and the ratio;
  * the add-on's frame update without Blender: Scene.evaluate_plies (the ply Animator) plus the float32
    conversion that feeds mesh.vertices.foreach_set, for ~N ply points.
Not a unit test: numbers depend on the machine and its load; run it on an idle machine.
"""
import argparse
import os
import subprocess
import sys
import time


def best(f, repeats=5):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def scene_with(knit, what, target):
    """A drape scene whose yarn (what='yarn') or ply point count is about `target`."""
    repeats = 16.0
    for _ in range(4):
        scene = knit.build_scene("stockinette", "drape", repeats=(repeats, repeats), res_u=128, res_v=128,
                                 build_plies=(what == "ply"))
        count = scene.stats[f"{what}_vertices"]
        repeats *= (target / count) ** 0.5
    return scene


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(os.path.dirname(__file__), "..", "build"))
    ap.add_argument("--yarn-points", type=int, default=1_000_000)
    args = ap.parse_args()
    path = os.path.abspath(os.path.join(args.build, "python"))
    sys.path.insert(0, path)
    import numpy as np
    import knit
    import knit._knit

    env = dict(os.environ, PYTHONPATH=path)
    imports = []
    for _ in range(5):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import knit"], check=True, env=env)
        imports.append(time.perf_counter() - t)
    empty = best(lambda: subprocess.run([sys.executable, "-c", "pass"], check=True))
    print(f"import knit: {min(imports) * 1e3:.0f} ms process (an empty interpreter: {empty * 1e3:.0f} ms)")

    scene = scene_with(knit, "yarn", args.yarn_points)
    pos64 = np.array(scene.mesh.positions) * 1.01
    pos32 = pos64.astype(np.float32)
    n = scene.yarns.point_count
    py64 = best(lambda: scene.evaluate(pos64))
    py32 = best(lambda: scene.evaluate(pos32))
    cpp = min(knit._knit._evaluate_seconds_in_cpp(scene, pos64, 1) for _ in range(5))
    print(f"evaluate {n} yarn points ({len(pos64)} mesh vertices): C++ {cpp * 1e3:.1f} ms, "
          f"Python float64 {py64 * 1e3:.1f} ms ({py64 / cpp:.2f}x), float32 {py32 * 1e3:.1f} ms ({py32 / cpp:.2f}x)")

    scene = scene_with(knit, "ply", args.yarn_points)
    pos = (np.array(scene.mesh.positions) * 1.01).astype(np.float32)
    m = scene.plies.point_count

    def frame():
        plies = scene.evaluate_plies(pos)
        return plies.points.astype(np.float32).ravel()  # what foreach_set("co", ...) receives

    print(f"add-on frame update (no Blender) for {m} ply points: {best(frame, 3) * 1e3:.0f} ms "
          f"(threads: all cores)")


main()
