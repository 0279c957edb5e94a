"""knit.distributed: bake a bound scene's frames on a Dask cluster, as a render farm would.

    import knit.distributed
    # once:  knit bind --mesh rest.obj --pattern rib.pyp --repeats 40 60 -o garment.knitbind
    knit.distributed.bake("garment.knitbind", "sim/frame_%04d.obj", "garment.pc2", chunk=10)

The frames are cut into chunks of `chunk` consecutive frame numbers; each chunk is one Dask task
that runs `knit animate --bound BOUND --frames FRAMES --first A --last B --threads T -o CHUNK` (the
command line a farm runs, so the bytes are the CLI's), and `knit cache merge` joins the chunks.
A frame is a pure function of the bound scene and its own mesh, so the merged cache equals one
`knit animate --bound BOUND --frames FRAMES -o OUT` run byte for byte, whatever the chunking, and
so the plain `knit animate --frames FRAMES [the bind's scene flags]` run: the bound file carries the
deformation `knit bind` chose as `knit animate` chooses it (--deform, --strain-table, the default),
with the strain table embedded, so workers need no strain table cache and take no deform options.

Failures: a chunk whose worker dies is run again by Dask on another worker (the knit process dies
with its worker: PR_SET_PDEATHSIG); a chunk that fails on bad input fails the bake with knit's
message (naming the frame and its file); every file appears whole or not at all (knit writes
through temporaries), and the merged output only once every chunk is there. The chunks of an
interrupted bake stay in `.<output>.chunks/` beside the output: the next bake with the same
arguments reuses them and runs only the missing ones.

The workers must see the same paths (a shared file system), the `knit` executable (`knit_cli`,
else $KNIT_CLI, else `knit` on PATH) and this package.
"""
import ctypes
import json
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import time
import uuid

from ._knit import Error, frame_numbers

__all__ = ["bake", "render_frames", "find_knit", "chunk_ranges"]

_PR_SET_PDEATHSIG = 1


def find_knit(knit_cli=None):
    """The knit executable: `knit_cli`, else $KNIT_CLI, else `knit` on PATH."""
    for candidate in (knit_cli, os.environ.get("KNIT_CLI"), shutil.which("knit")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    raise Error("knit_cli: no knit executable (pass knit_cli=, set KNIT_CLI or put knit on PATH)")


def chunk_ranges(numbers, chunk):
    """Consecutive runs of `chunk` frame numbers: [(first, last), ...]."""
    return [(numbers[i], numbers[min(i + chunk, len(numbers)) - 1]) for i in range(0, len(numbers), chunk)]


def _die_with_parent():
    # The knit process ends with the worker that started it (a killed worker leaves none behind).
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


class ChunkFailed(Exception):
    """A chunk's knit run failed on its input (not retried)."""


def _run_chunk(command, first, last):
    """Runs one chunk's knit command (or a list of commands) on a worker; returns its wall seconds."""
    start = time.monotonic()
    for one in command if isinstance(command[0], list) else [command]:
        proc = subprocess.run(one, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              preexec_fn=_die_with_parent, check=False)
        if proc.returncode != 0:
            message = (proc.stderr.strip() or proc.stdout.strip()).replace("knit: error: ", "")
            raise ChunkFailed("frames %d-%d: %s" % (first, last, message))
    return time.monotonic() - start


def _pc2_range(path):
    """(start, frames, step) of a complete PC2 file, or None."""
    try:
        with open(path, "rb") as f:
            head = f.read(32)
        if len(head) != 32 or head[:12] != b"POINTCACHE2\0":
            return None
        _, points, start, step, frames = struct.unpack("<iiffi", head[12:])
        if os.path.getsize(path) != 32 + 12 * points * frames:
            return None
        return int(start), frames, int(step)
    except OSError:
        return None


def _mdd_range(path):
    """(start, frames, step) of a complete MDD file with its topology .obj (which records an MDD's
    frames: knit cache merge reads them), or None."""
    try:
        with open(path, "rb") as f:
            frames, points = struct.unpack(">ii", f.read(8))
        if frames < 1 or os.path.getsize(path) != 8 + 4 * frames + 12 * points * frames:
            return None
        with open(path[:-4] + ".obj") as f:
            m = re.search(r"; MDD frames (-?\d+)-(-?\d+) step (\d+) at \S+ fps$", f.readline().rstrip("\n"))
        return (int(m.group(1)), frames, int(m.group(3))) if m else None
    except (OSError, struct.error):
        return None


def _check_args(bound, frames, output, chunk, step):
    if not isinstance(bound, str) or not os.path.isfile(bound):
        raise Error("bound: '%s' is not a file (write one with `knit bind`)" % (bound,))
    if not isinstance(frames, str) or not frames:
        raise Error("frames: give the mesh sequence as `knit animate --frames` takes it")
    if not isinstance(chunk, int) or isinstance(chunk, bool) or chunk < 1:
        raise Error("chunk: the frames per task must be a positive integer (got %r)" % (chunk,))
    if not isinstance(step, int) or isinstance(step, bool) or step < 1:
        raise Error("step: must be a positive integer (got %r)" % (step,))
    per_frame = "%" in os.path.basename(output)
    if not per_frame and not output.lower().endswith((".pc2", ".mdd")):
        raise Error("output: '%s': give a .pc2 or .mdd (merged from the chunks) or a per-frame pattern such as "
                    "out_%%04d.glb" % output)
    return per_frame


def _check_bake_args(fps, threads, export):
    """bake()'s settings passed on to `knit animate`, checked here so that a bad one is named by its keyword
    before any cluster starts (the command line would name its own flags)."""
    if isinstance(fps, bool) or not isinstance(fps, (int, float)) or not (0.001 <= fps <= 1e6):
        raise Error("fps: must be a frame rate of 0.001 to 1e6 frames per second (got %r)" % (fps,))
    if not isinstance(threads, int) or isinstance(threads, bool) or threads < 0:
        raise Error("threads: must be an integer >= 0, 0 = all cores (got %r)" % (threads,))
    if export not in ("plies", "yarns"):
        raise Error("export: must be 'plies' or 'yarns' (got %r)" % (export,))


def _start_cluster(workers):
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                           silence_logs=40)
    return cluster, Client(cluster)


def _job_folder(output, manifest):
    """The chunk folder beside `output`; chunks of another job there are removed (no stale reuse)."""
    folder = os.path.join(os.path.dirname(os.path.abspath(output)), "." + os.path.basename(output) + ".chunks")
    path = os.path.join(folder, "job.json")
    try:
        with open(path) as f:
            same = json.load(f) == manifest
    except (OSError, ValueError):
        same = False
    if not same:
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder, exist_ok=True)
        with open(path + ".tmp", "w") as f:
            json.dump(manifest, f)
        os.replace(path + ".tmp", path)
    return folder


def _fan_out(client, jobs, progress, what, timeout):
    """Runs (label, command, first, last) jobs as tasks; returns {label: seconds}. Raises Error for a
    failed chunk (a worker that died is not a failure: Dask runs its task again elsewhere)."""
    from distributed import TimeoutError as DaskTimeout
    from distributed import wait

    token = uuid.uuid4().hex[:12]  # task keys unique to this bake (a resumed bake may overlap an old one)
    futures = {client.submit(_run_chunk, command, a, b, key="knit-%s-%s" % (label, token), pure=False,
                             retries=0): label for label, command, a, b in jobs}
    seconds = {}
    pending = set(futures)
    deadline = None if timeout is None else time.monotonic() + timeout
    try:
        while pending:
            left = None if deadline is None else max(deadline - time.monotonic(), 0.001)
            done, pending = wait(list(pending), timeout=left, return_when="FIRST_COMPLETED")
            for future in done:
                if future.status != "finished":
                    raise Error("%s failed: %s" % (what, future.exception())) from None
                seconds[futures[future]] = future.result()
                if progress:
                    progress("%s %s done (%d/%d)" % (what, futures[future], len(seconds), len(futures)))
    except (DaskTimeout, TimeoutError):
        raise Error("timeout: the %ss did not finish within %s s" % (what, timeout)) from None
    finally:
        client.cancel(list(futures))
    return seconds


def _stderr_progress(message):
    print("knit.distributed: " + message, file=sys.stderr, flush=True)


def bake(bound, frames, output, client=None, chunk=10, first=-1, last=-1, step=1, fps=24.0, threads=1,
         export="plies", knit_cli=None, progress=True, workers=None, timeout=None):
    """Bakes the frames of a bound scene (`knit bind`) into `output` on a Dask cluster.

    bound: the bound scene file. frames: the mesh sequence as `knit animate --frames` takes it;
    first / last / step: its frame numbers (-1: the files found). output: a .pc2 or .mdd (chunks
    merged, its topology .obj beside it) or a per-frame pattern such as out_%04d.glb (no merge). client: a
    distributed.Client; None starts a LocalCluster of `workers` (default: one per core) single-
    threaded workers and closes it at the end. chunk: frames per task. threads: knit's threads per
    task. export: plies or yarns. progress: True (lines on stderr), False, or a callable taking a
    message. timeout: seconds for all chunks (None: no limit). Returns a dict: frames, chunks, reused (chunks kept from an earlier run), seconds,
    chunk_seconds (per chunk key). Raises knit.Error naming the frame and file of a failed chunk.
    """
    per_frame = _check_args(bound, frames, output, chunk, step)
    _check_bake_args(fps, threads, export)
    output = os.path.abspath(output)
    knit_exe = find_knit(knit_cli)
    report = progress if callable(progress) else (_stderr_progress if progress else None)
    start = time.monotonic()
    numbers = frame_numbers(frames, first, last, step)
    ranges = chunk_ranges(numbers, chunk)
    base = [knit_exe, "animate", "-q", "--no-stats", "--bound", os.path.abspath(bound), "--frames",
            os.path.abspath(frames), "--step", str(step), "--fps", repr(fps),
            "--threads", str(threads), "--export", export]
    # Step 1: the chunks still to run (a resumed bake reuses the complete ones of the same job).
    jobs, chunk_files, reused = [], [], 0
    if per_frame:
        for a, b in ranges:
            files = [output % n for n in numbers if a <= n <= b]
            if all(os.path.exists(f) for f in files):
                reused += 1
                continue
            jobs.append(("frames-%d-%d" % (a, b), base + ["--first", str(a), "--last", str(b), "-o", output], a, b))
    else:
        stat = os.stat(bound)
        manifest = {"bound": os.path.abspath(bound), "size": stat.st_size, "mtime": stat.st_mtime_ns,
                    "frames": frames, "numbers": numbers, "chunk": chunk, "fps": fps, "export": export}
        folder = _job_folder(output, manifest)
        for a, b in ranges:
            extension = output[-4:].lower()  # the chunks are of the output's format (.pc2 or .mdd)
            path = os.path.join(folder, "chunk_%08d_%08d%s" % (a, b, extension))
            chunk_files.append(path)
            count = len([n for n in numbers if a <= n <= b])
            complete = _mdd_range(path) if extension == ".mdd" else _pc2_range(path)
            if complete == (a, count, step) and os.path.exists(path[:-4] + ".obj"):
                reused += 1
                continue
            jobs.append(("frames-%d-%d" % (a, b), base + ["--first", str(a), "--last", str(b), "-o", path], a, b))
    if report and reused:
        report("%d of %d chunks kept from an earlier run" % (reused, len(ranges)))
    # Step 2: the chunks as tasks.
    cluster = None
    if client is None and jobs:
        cluster, client = _start_cluster(workers or os.cpu_count() or 1)
    try:
        seconds = _fan_out(client, jobs, report, "chunk", timeout) if jobs else {}
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
    # Step 3: one cache from the chunks (written atomically by knit), then the chunks go.
    if not per_frame:
        merged = subprocess.run([knit_exe, "cache", "merge"] + chunk_files + ["-o", output], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, check=False)
        if merged.returncode != 0:
            raise Error("merging the chunks into '%s' failed: %s" % (output, merged.stderr.strip()))
        shutil.rmtree(os.path.dirname(chunk_files[0]), ignore_errors=True)
    return {"frames": len(numbers), "chunks": len(ranges), "reused": reused, "seconds": time.monotonic() - start,
            "chunk_seconds": seconds}


def render_frames(bound, frames, output, client=None, chunk=1, first=-1, last=-1, step=1, render_args=(),
                  knit_cli=None, progress=True, workers=None, timeout=None):
    """Renders each frame of a bound scene on a Dask cluster: `knit render --bound BOUND --frame-mesh
    FRAME_k [render_args] --output OUTPUT_k` (`output` a pattern such as out_%04d.png; render_args e.g.
    ["--width", "960", "--spp", "64"]), `chunk` frames per task. Frames whose image exists are kept
    (a resumed render redoes only the missing ones); each image is written atomically by knit.
    client / workers / progress / timeout as in bake(). Returns a dict: frames, chunks, reused,
    seconds, chunk_seconds. Raises knit.Error naming the frame and file of a failed render.
    """
    _check_args(bound, frames, output, chunk, step)
    # A string was iterated as one argument per character ("The following arguments were not expected: 0 p p s").
    if isinstance(render_args, (str, bytes)) or not all(isinstance(a, str) for a in render_args):
        raise TypeError("render_args: expected a list of `knit render` arguments (str each), got %r" % (render_args,))
    if "%" not in os.path.basename(output):
        raise Error("output: '%s': give a per-frame pattern such as out_%%04d.png" % output)
    output = os.path.abspath(output)
    knit_exe = find_knit(knit_cli)
    report = progress if callable(progress) else (_stderr_progress if progress else None)
    start = time.monotonic()
    numbers = frame_numbers(frames, first, last, step)
    frames = os.path.abspath(frames)
    jobs, reused = [], 0
    for a, b in chunk_ranges(numbers, chunk):
        todo = [n for n in numbers if a <= n <= b and not os.path.exists(output % n)]
        if not todo:
            reused += 1
            continue
        # The frame's mesh file as `knit animate` finds it (a printf pattern; a folder's files by number).
        commands = [[knit_exe, "render", "-q", "--bound", os.path.abspath(bound), "--frame-mesh", _frame_file(frames, n)]
                    + [str(x) for x in render_args] + ["--output", output % n] for n in todo]
        jobs.append(("render-%d-%d" % (a, b), commands, a, b))
    cluster = None
    if client is None and jobs:
        cluster, client = _start_cluster(workers or os.cpu_count() or 1)
    try:
        seconds = _fan_out(client, jobs, report, "render", timeout) if jobs else {}
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
    return {"frames": len(numbers), "chunks": len(jobs) + reused, "reused": reused,
            "seconds": time.monotonic() - start, "chunk_seconds": seconds}


def _frame_file(frames, number):
    if "%" in os.path.basename(frames):
        return frames % number
    raise Error("frames: render_frames takes a printf pattern such as frames/frame_%04d.obj")
