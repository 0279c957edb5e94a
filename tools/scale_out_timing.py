"""The numbers of docs/scale-out.md: a bound scene's frames baked three ways, and the bind / load costs.

    /usr/bin/python3 tools/scale_out_timing.py [--build build] [--dir DIR] [--frames 60] [--res 40]
                                               [--repeats 15] [--chunk 10]

Writes a 0.3 m cloth (res x res quads) under a wave as OBJ frames into DIR (default a temporary
folder; /dev/shm keeps the disk out of it), binds the hylc stockinette (KNIT_SHARED_DIR) or the
built-in one on frame 1 with `knit bind`, then, one after the other:
  * `knit animate --bound ... -o one.pc2` (every core),
  * knit.distributed.bake on a LocalCluster of 1 single-threaded worker (knit --threads 1),
  * the same on 2 single-threaded workers,
checks the bakes' bytes equal the single run's, and prints wall and CPU seconds of each, the
scheduling overhead per chunk ((workers x wall - sum of the chunks' knit wall times) / chunks,
merge included), the bind and load CPU seconds (median of 5, in-process; the scene only, without
the Animator: bench/bound_scene_bench measures both with it), the bound file's size
and the output bytes per frame. Not a unit test: numbers depend on the machine and its load.
"""
import argparse
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time


def write_frames(folder, res, frames):
    for k in range(1, frames + 1):
        lines = []
        for j in range(res + 1):
            for i in range(res + 1):
                x, y = 0.3 * i / res, 0.3 * j / res
                z = 0.01 * (k - 1) / frames * math.sin(20 * x + 0.3 * k) * math.cos(10 * y)
                lines.append("v %r %r %r" % (x, y, z))
        lines += ["vt %r %r" % (i / res, j / res) for j in range(res + 1) for i in range(res + 1)]
        for j in range(res):
            for i in range(res):
                a = j * (res + 1) + i + 1
                b, c, d = a + 1, a + res + 2, a + res + 1
                lines.append("f %d/%d %d/%d %d/%d" % (a, a, b, b, c, c))
                lines.append("f %d/%d %d/%d %d/%d" % (a, a, c, c, d, d))
        with open(os.path.join(folder, "frame_%04d.obj" % k), "w") as out:
            out.write("\n".join(lines) + "\n")


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def self_cpu():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def bake_on(kd, distributed, workers, bound, frames, out, chunk, knit_cli):
    cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=50)
    client = distributed.Client(cluster)
    try:
        t0 = time.monotonic()
        r = kd.bake(bound, frames, out, client=client, chunk=chunk, threads=1, progress=False, knit_cli=knit_cli)
        wall = time.monotonic() - t0
        # The workers' CPU (their knit children are reaped by the workers, not by us).
        return wall, r
    finally:
        client.close()
        cluster.close()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--dir", default=None)
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--res", type=int, default=40)
    ap.add_argument("--repeats", type=float, default=15)
    ap.add_argument("--chunk", type=int, default=10)
    a = ap.parse_args()
    sys.path.insert(0, os.path.abspath(os.path.join(a.build, "python")))
    os.environ["PYTHONPATH"] = os.path.abspath(os.path.join(a.build, "python"))
    import distributed

    import knit
    import knit.distributed as kd

    knit_cli = os.path.abspath(os.path.join(a.build, "apps", "knit", "knit"))
    folder = a.dir or tempfile.mkdtemp(prefix="knit_scale_out_")
    os.makedirs(folder, exist_ok=True)
    write_frames(folder, a.res, a.frames)
    shared = os.environ.get("KNIT_SHARED_DIR", "")
    pattern = os.path.join(shared, "patterns", "hylc", "stockinette.pyp")
    pattern = pattern if os.path.isfile(pattern) else "stockinette"
    frames, bound = os.path.join(folder, "frame_%04d.obj"), os.path.join(folder, "g.knitbind")
    rep = "%g" % a.repeats
    subprocess.run([knit_cli, "bind", "-q", "--mesh", os.path.join(folder, "frame_0001.obj"), "--pattern", pattern,
                    "--repeats", rep, rep, "-o", bound], check=True)

    # Bind vs load, in-process CPU seconds (median of 5).
    mesh = knit.load_mesh(os.path.join(folder, "frame_0001.obj"))
    binds, loads = [], []
    for _ in range(5):
        c = self_cpu()
        knit.build_scene(pattern, mesh, repeats=(a.repeats, a.repeats), build_plies=False)
        binds.append(self_cpu() - c)
        c = self_cpu()
        knit.load_bound_scene(bound)
        loads.append(self_cpu() - c)

    # One multi-threaded run.
    one = os.path.join(folder, "one.pc2")
    c, t0 = children_cpu(), time.monotonic()
    subprocess.run([knit_cli, "animate", "-q", "--no-stats", "--bound", bound, "--frames", frames, "-o", one],
                   check=True)
    single_wall, single_cpu = time.monotonic() - t0, children_cpu() - c
    with open(one, "rb") as f:
        reference = f.read()
    os.remove(one)

    rows = []
    for workers in (1, 2):
        out = os.path.join(folder, "dask%d.pc2" % workers)
        wall, r = bake_on(kd, distributed, workers, bound, frames, out, a.chunk, knit_cli)
        with open(out, "rb") as f:
            same = f.read() == reference
        os.remove(out)
        os.remove(out[:-4] + ".obj")
        busy = sum(r["chunk_seconds"].values())
        rows.append((workers, wall, busy, r["chunks"], same))

    print("frames %d, mesh %d triangles, ply points per frame %d, output %.2f MB per frame, bound file %.2f MB"
          % (a.frames, 2 * a.res * a.res, (len(reference) - 32) // 12 // a.frames,
             (len(reference) - 32) / a.frames / 1e6, os.path.getsize(bound) / 1e6))
    print("bind CPU %.3f s, load CPU %.3f s (median of 5, in-process)"
          % (statistics.median(binds), statistics.median(loads)))
    print("knit animate --bound (every core): wall %.2f s, CPU %.2f s" % (single_wall, single_cpu))
    for workers, wall, busy, chunks, same in rows:
        print("dask %d worker(s) x 1 thread, %d chunks of %d: wall %.2f s (%.2fx the 1-worker bake, %.2fx knit "
              "animate), chunks' knit time %.2f s, overhead %.3f s per chunk, bytes equal: %s"
              % (workers, chunks, a.chunk, wall, rows[0][1] / wall, wall / single_wall, busy,
                 (workers * wall - busy) / chunks, same))
    print("load average (1, 5, 15 min): %.1f %.1f %.1f on %d cores" % (os.getloadavg() + (os.cpu_count(),)))


if __name__ == "__main__":
    main()
