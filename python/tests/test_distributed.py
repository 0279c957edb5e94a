# knit.distributed on a local Dask cluster the tests start and stop themselves (bounded
# timeouts, no process left behind): the cluster's bytes equal one `knit animate` run, also when
# a worker is killed in the middle of a chunk; bad input fails the bake naming the frame and
# file; an interrupted bake leaves no output and is resumed redoing only the missing chunks.
import math
import os
import signal
import subprocess
import threading
import time

import pytest

import knit

distributed = pytest.importorskip("distributed")
import knit.distributed as kd  # noqa: E402

from test_animation import knit_cli  # noqa: E402

KNIT = knit_cli()
pytestmark = pytest.mark.skipif(KNIT is None, reason="the knit command line is not built")


def write_wave(path, k, n):
    """An n x n quad grid (0.1 m square, UVs in [0, 1]) with a wave growing with frame k."""
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = 0.1 * i / n, 0.1 * j / n
            lines.append("v %r %r %r" % (x, y, 0.003 * (k - 1) * math.sin(60 * x + 0.3 * k)))
    lines += ["vt %r %r" % (i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c, d = a + 1, a + n + 2, a + n + 1
            lines.append("f %d/%d %d/%d %d/%d" % (a, a, b, b, c, c))
            lines.append("f %d/%d %d/%d %d/%d" % (a, a, c, c, d, d))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def run(*args, cwd):
    proc = subprocess.run([KNIT] + list(args), cwd=cwd, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    return proc


def read(path):
    with open(path, "rb") as f:
        return f.read()


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A 2-worker LocalCluster (processes), closed with bounded timeouts; afterwards no worker or
    knit process of it is left."""
    # The workers import knit.distributed: they need the package's folder on their path.
    os.environ["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.dirname(knit.__file__))] +
                                               [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    local = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                     silence_logs=50, timeout=30)
    client = distributed.Client(local, timeout=30)
    pids = set()
    yield client, pids
    pids.update(client.run(os.getpid, wait=True).values())
    client.close(timeout=10)
    local.close(timeout=10)
    for pid in pids:
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)
    # knit processes of these tests (other test binaries may run knit meanwhile: ctest -j).
    assert knit_processes(str(tmp_path_factory.getbasetemp())) == [], "knit processes left behind"


def knit_processes(under=None):
    """Pids of running knit executables of this build (with an argument under `under`, if given)."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % entry, "rb") as f:
                argv = f.read().split(b"\0")
            with open("/proc/%s/stat" % entry) as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if argv and argv[0] == KNIT.encode() and state != "Z":
            if under is None or any(under.encode() in a for a in argv):
                found.append(int(entry))
    return found


def parent_of(pid):
    with open("/proc/%d/stat" % pid) as f:
        return int(f.read().rsplit(")", 1)[1].split()[1])


@pytest.fixture
def sequence(tmp_path):
    """12 frames of a wave and the scene bound on the first (`knit bind`)."""
    for k in range(1, 13):
        write_wave(tmp_path / ("frame_%04d.obj" % k), k, 10)
    run("bind", "-q", "--mesh", "frame_0001.obj", "--repeats", "4", "4", "-o", "g.knitbind", cwd=tmp_path)
    return tmp_path


def test_cluster_bake_equals_knit_animate_and_an_interrupted_bake_resumes(cluster, sequence):
    client, pids = cluster
    pids.update(client.run(os.getpid).values())
    d = sequence
    run("animate", "-q", "--bound", "g.knitbind", "--frames", "frame_%04d.obj", "-o", "one.pc2", cwd=d)
    # An interrupted bake (stopped after its first chunk): no output; its finished chunks stay.
    messages = []

    def stop_after_first(message):
        messages.append(message)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.pc2"), client=client, chunk=3,
                progress=stop_after_first, knit_cli=KNIT, timeout=60)
    assert not (d / "all.pc2").exists() and not (d / "all.obj").exists()
    # Resumed: only the missing chunks run; the bytes are the single run's.
    result = kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.pc2"), client=client, chunk=3,
                     progress=messages.append, knit_cli=KNIT, timeout=60)
    assert result["frames"] == 12 and result["chunks"] == 4
    assert result["reused"] >= 1 and len(result["chunk_seconds"]) == 4 - result["reused"]
    assert read(d / "all.pc2") == read(d / "one.pc2")
    assert read(d / "all.obj") == read(d / "one.obj")
    assert not (d / ".all.pc2.chunks").exists()
    # Per-frame outputs need no merge: each frame file is the single run's.
    run("animate", "-q", "--bound", "g.knitbind", "--frames", "frame_%04d.obj", "--export", "yarns", "-o",
        "one_%04d.obj", cwd=d)
    kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "f_%04d.obj"), client=client, chunk=5,
            export="yarns", progress=False, knit_cli=KNIT, timeout=60)
    for k in range(1, 13):
        assert read(d / ("f_%04d.obj" % k)) == read(d / ("one_%04d.obj" % k)), k
    # An MDD bake: chunks of MDD merged (their frames recorded in their .obj) to the single run's bytes.
    run("animate", "-q", "--bound", "g.knitbind", "--frames", "frame_%04d.obj", "-o", "one.mdd", cwd=d)
    kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.mdd"), client=client, chunk=5,
            progress=False, knit_cli=KNIT, timeout=60)
    assert read(d / "all.mdd") == read(d / "one.mdd")
    assert read(d / "all.obj") == read(d / "one.obj")


def test_render_frames_equal_knit_render_of_each_frame(cluster, sequence):
    client, _ = cluster
    d = sequence
    size = ["--width", "32", "--height", "24", "--spp", "2"]
    result = kd.render_frames(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "r_%04d.png"), client=client,
                              chunk=2, first=3, last=5, render_args=size, progress=False, knit_cli=KNIT, timeout=60)
    assert result["frames"] == 3 and result["chunks"] == 2
    for k in (3, 4, 5):
        run("render", "-q", "--bound", "g.knitbind", "--frame-mesh", "frame_%04d.obj" % k, *size, "--output",
            "one_%04d.png" % k, cwd=d)
        assert read(d / ("r_%04d.png" % k)) == read(d / ("one_%04d.png" % k)), k
    assert not (d / "r_0002.png").exists()
    os.remove(d / "r_0004.png")  # resumed: only the missing frame's chunk runs again
    result = kd.render_frames(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "r_%04d.png"), client=client,
                              chunk=2, first=3, last=5, render_args=size, progress=False, knit_cli=KNIT, timeout=60)
    assert result["reused"] == 1 and read(d / "r_0004.png") == read(d / "one_0004.png")


def test_bad_input_fails_the_bake_naming_the_frame_and_file(cluster, sequence):
    client, _ = cluster
    d = sequence
    write_wave(d / "frame_0007.obj", 7, 9)  # another mesh: 100 vertices, not 121
    with pytest.raises(knit.Error, match=r"frame 7 \('[^']*frame_0007\.obj'\)"):
        kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.pc2"), client=client, chunk=4,
                progress=False, knit_cli=KNIT, timeout=60)
    assert not (d / "all.pc2").exists()
    with pytest.raises(knit.Error, match="chunk: the frames per task"):
        kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.pc2"), client=client, chunk=0)
    with pytest.raises(knit.Error, match="frame 13"):
        kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.pc2"), client=client, last=13)


def test_a_worker_killed_mid_chunk_gives_the_same_complete_output(cluster, tmp_path):
    client, pids = cluster
    d = tmp_path
    for k in range(1, 9):
        write_wave(d / ("frame_%04d.obj" % k), k, 30)
    # A scene whose chunks take long enough to be killed in (about 0.5 s for 4 frames).
    run("bind", "-q", "--mesh", "frame_0001.obj", "--repeats", "40", "40", "--samples-per-turn", "24", "-o",
        "g.knitbind", cwd=d)
    run("animate", "-q", "--bound", "g.knitbind", "--frames", "frame_%04d.obj", "-o", "one.pc2", cwd=d)
    workers = client.run(os.getpid)
    pids.update(workers.values())
    outcome = {}

    def bake():
        try:
            outcome["result"] = kd.bake(str(d / "g.knitbind"), str(d / "frame_%04d.obj"), str(d / "all.pc2"),
                                        client=client, chunk=4, progress=False, knit_cli=KNIT, timeout=120)
        except BaseException as e:  # reported by the assertions below
            outcome["error"] = e

    thread = threading.Thread(target=bake)
    thread.start()
    # Kill the worker process running a chunk's knit, while it runs.
    killed = None
    deadline = time.monotonic() + 30
    while killed is None and time.monotonic() < deadline and thread.is_alive():
        for pid in knit_processes():
            try:
                parent = parent_of(pid)
            except OSError:
                continue
            if parent in workers.values():
                os.kill(parent, signal.SIGKILL)
                killed = (parent, pid)
                break
        time.sleep(0.005)
    assert killed is not None, "no chunk was caught running"
    # The killed worker's knit process dies with it (at once: not by finishing its chunk, ~0.5 s).
    deadline = time.monotonic() + 0.2
    while killed[1] in knit_processes() and time.monotonic() < deadline:
        time.sleep(0.01)
    gone = killed[1] not in knit_processes()
    thread.join(timeout=150)
    assert not thread.is_alive(), "the bake did not finish"
    assert gone, "the killed worker's knit process outlived it"
    assert "error" not in outcome, outcome.get("error")
    assert read(d / "all.pc2") == read(d / "one.pc2")
    pids.update(client.run(os.getpid).values())  # the restarted worker, closed with the cluster
