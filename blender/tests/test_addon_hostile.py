"""Headless hostile-input test of the add-on's operators (issue 29; run by ctest as
blender_addon_hostile: blender -b --factory-startup --python-exit-code 1 --python ...).

Apply Knit with absurd properties (a missing, empty or device pattern file, an unknown chart text
block or a chart that does not parse, repeats or a gauge far outside any garment, a tiny ply pitch),
on a mesh without UVs or without faces, and Bake Knit to PC2 into a folder, a missing folder or
over the source's own file: every one either makes a finite knit or is refused in the interface
(an ERROR report: RuntimeError in background mode) whose message names the operator's properties,
never a command-line flag or a Python keyword, with no traceback printed, no object left behind by
a refusal and no file written. A Blender killed mid-bake (a child Blender, SIGKILL at frame 3)
leaves only a hidden temporary, which the next knit write into that folder removes."""
import contextlib
import io
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import knit_blender  # noqa: E402
from addon_scene import make_animated_grid, points_of  # noqa: E402

FOREIGN = ["--", "res_u", "max_memory", "ply_pitch", "samples_per_turn", "positions:", "Traceback", "::"]


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        raise SystemExit(f"knit_blender test failed: {what}")


def run(op, **props):
    """Runs an operator; returns (result, message, printed)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            return op(**props), "", out.getvalue() + err.getvalue()
        except RuntimeError as e:  # an ERROR report in background mode
            return {"CANCELLED"}, str(e), out.getvalue() + err.getvalue()


def select(obj):
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def expect_refused_or_finite(source, what, words=None, **props):
    select(source)
    names = set(bpy.data.objects.keys())
    result, message, printed = run(bpy.ops.object.knit_apply, **props)
    check("Traceback" not in printed and "Traceback" not in message, f"{what}: no traceback")
    if result == {"FINISHED"}:
        new = [bpy.data.objects[n] for n in set(bpy.data.objects.keys()) - names]
        check(all(np.all(np.isfinite(points_of(o))) for o in new), f"{what}: a finite knit")
        check(words is None, f"{what}: refused (it was accepted)")
        for o in new:
            bpy.data.objects.remove(o)
        return
    check(set(bpy.data.objects.keys()) == names, f"{what}: a refusal leaves no object")
    check(not any(f in message for f in FOREIGN), f"{what}: the message names no flag or keyword ({message!r})")
    if words:
        check(all(w in message for w in words), f"{what}: the message says {words} ({message!r})")


def main():
    knit_blender.register()
    folder = tempfile.mkdtemp(prefix="knit-blender-hostile-")
    empty = os.path.join(folder, "empty.pyp")
    open(empty, "w").close()
    cloth = make_animated_grid()

    expect_refused_or_finite(cloth, "a missing pattern file", ["missing.pyp"],
                             pattern=os.path.join(folder, "missing.pyp"))
    expect_refused_or_finite(cloth, "an empty pattern file", ["empty.pyp"], pattern=empty)
    expect_refused_or_finite(cloth, "a folder as the pattern", [folder], pattern=folder)
    expect_refused_or_finite(cloth, "a device as the pattern", ["/dev/zero"], pattern="/dev/zero")
    expect_refused_or_finite(cloth, "an empty pattern name", [], pattern="")
    expect_refused_or_finite(cloth, "an unknown chart text block", ["Chart text"], chart_text="no such block")
    bad = bpy.data.texts.new("bad chart")
    bad.write("k zz\nk k\n")
    expect_refused_or_finite(cloth, "a chart that does not parse", ["zz"], chart_text="bad chart")
    wide = bpy.data.texts.new("wide chart")
    wide.write("k" * 20000 + "\n")
    expect_refused_or_finite(cloth, "a 20000-character token", ["20000 characters"], chart_text="wide chart")
    check(len(run(bpy.ops.object.knit_apply, chart_text="wide chart")[1]) < 1000, "a long token is not echoed whole")
    expect_refused_or_finite(cloth, "repeats far beyond any garment", ["Repeats"], repeats=(1e9, 1e9))
    expect_refused_or_finite(cloth, "a gauge far beyond any garment", ["the repeats (from Gauge)"], repeats=(0, 0),
                             gauge=(1e9, 1e9))
    expect_refused_or_finite(cloth, "repeats of a billionth", None, repeats=(1e-9, 1e-9))
    expect_refused_or_finite(cloth, "a ply pitch of a picometre", ["Ply pitch"], ply_pitch=1e-12)

    # Found by tools/hostile_blender.py (issue 29, the Blender round): a property set on one axis
    # only (ignored before), an empty chart text block (Pattern used instead, silently), a Blender
    # file as the pattern (read as a .pyp), Strain-aware on a pattern whose table would take minutes
    # to make (Blender not responding for them).
    expect_refused_or_finite(cloth, "Repeats on one axis", ["Repeats (0, 5)", "both"], repeats=(0, 5))
    expect_refused_or_finite(cloth, "Gauge on one axis", ["Gauge (20, 0)", "both"], repeats=(0, 0), gauge=(20, 0))
    bpy.data.texts.new("empty chart")
    expect_refused_or_finite(cloth, "an empty chart text block", ["'empty chart' is empty"], chart_text="empty chart")
    slow = bpy.data.texts.new("slow chart")
    slow.write("k p k p\nk p k p\n")
    cache = os.environ.get("KNIT_CACHE_DIR")
    os.environ["KNIT_CACHE_DIR"] = os.path.join(folder, "cache")  # no table of it cached (nor stockinette's)
    started = time.monotonic()
    expect_refused_or_finite(cloth, "Strain-aware with a table that takes minutes", ["Deform Strain-aware", "minutes"],
                             chart_text="slow chart", repeats=(4, 4), deform="strain")
    check(time.monotonic() - started < 30, f"refused without making it ({time.monotonic() - started:.1f} s)")
    if cache is None:
        del os.environ["KNIT_CACHE_DIR"]
    else:
        os.environ["KNIT_CACHE_DIR"] = cache
    nan_mesh = bpy.data.meshes.new("nan")
    nan_mesh.from_pydata([(0, 0, 0), (1, 0, 0), (float("nan"), 1, 0), (0, 1, 0)], [], [(0, 1, 2, 3)])
    nan_mesh.uv_layers.new(name="UVMap")
    nan_obj = bpy.data.objects.new("NaN", nan_mesh)
    bpy.context.scene.collection.objects.link(nan_obj)
    expect_refused_or_finite(nan_obj, "a NaN vertex", ["the source's vertex 2", "not finite"])

    # Meshes the knit cannot bind to.
    bpy.ops.mesh.primitive_plane_add(size=1)
    no_uv = bpy.context.active_object
    no_uv.data.uv_layers.remove(no_uv.data.uv_layers[0])
    expect_refused_or_finite(no_uv, "a mesh without UVs", ["UV"])
    mesh = bpy.data.meshes.new("points only")
    mesh.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [])
    points = bpy.data.objects.new("Points", mesh)
    bpy.context.scene.collection.objects.link(points)
    expect_refused_or_finite(points, "a mesh without faces", [])

    # Bake to PC2 into places it cannot write: nothing written, no traceback.
    select(cloth)
    check(run(bpy.ops.object.knit_apply, pattern="stockinette", repeats=(4, 4))[0] == {"FINISHED"}, "a good knit")
    knit_obj = bpy.data.objects[f"{cloth.name}.knit"]
    before = sorted(os.listdir(folder))
    for path, what in [(folder, "a folder"), (os.path.join(folder, "missing", "c.pc2"), "a missing folder"),
                       (empty, "a file that is not .pc2")]:
        select(knit_obj)
        result, message, printed = run(bpy.ops.object.knit_bake_pc2, filepath=path, frame_start=1, frame_end=3)
        check(result == {"CANCELLED"} and "Traceback" not in printed, f"bake into {what}: refused ({message!r})")
        check(not any(f in message for f in FOREIGN), f"bake into {what}: names no flag or keyword")
        check(sorted(os.listdir(folder)) == before, f"bake into {what}: nothing written")
    select(knit_obj)
    result, message, _ = run(bpy.ops.object.knit_bake_pc2, filepath=os.path.join(folder, "c.pc2"), frame_start=5,
                             frame_end=2)
    check(result == {"CANCELLED"} and "End (2) is before Start (5)" in message, "bake End before Start: refused")
    for props, words, what in [(dict(frame_start=1, frame_end=2), ["not saved"], "the default // path, unsaved"),
                               (dict(filepath="//c.pc2", frame_start=1, frame_end=2), ["not saved"],
                                "//c.pc2, unsaved"),
                               (dict(filepath=os.path.join(folder, "c.pc2"), frame_start=1, frame_end=2**31 - 1),
                                ["End (2147483647) is beyond Blender's frames"], "End 2^31 - 1")]:
        select(knit_obj)
        result, message, printed = run(bpy.ops.object.knit_bake_pc2, **props)
        check(result == {"CANCELLED"} and all(w in message for w in words) and "Traceback" not in printed,
              f"bake {what}: refused ({message.strip()!r})")
        check(sorted(os.listdir(folder)) == before and not os.path.exists(f"{knit_obj.name}.pc2"),
              f"bake {what}: nothing written (here or where Blender started)")
    knit_obj["knit_options"] = "{damaged"
    select(knit_obj)
    result, message, printed = run(bpy.ops.object.knit_reapply)
    check(result == {"CANCELLED"} and "knit_options" in message and "Apply Knit" in message,
          f"Re-apply with damaged stored options: refused, saying what to do ({message.strip()!r})")
    # Saved: a pattern beside the .blend file given //-relative is found; the .blend is no pattern.
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(folder, "scene.blend"))
    shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "patterns", "stockinette.pyp"),
                os.path.join(folder, "p.pyp"))
    select(cloth)
    check(run(bpy.ops.object.knit_apply, pattern="//p.pyp", repeats=(4, 4))[0] == {"FINISHED"},
          "a pattern given relative to the .blend file (//p.pyp) is found")
    knit_obj = bpy.data.objects[f"{cloth.name}.knit"]
    expect_refused_or_finite(cloth, "the .blend file as the pattern", ["scene.blend", "Blender file"],
                             pattern=os.path.join(folder, "scene.blend"))
    killed_bake(folder, knit_obj)
    print("knit_blender hostile test passed")


def bake_and_die(folder):
    """The child Blender: Apply Knit, then Bake to PC2 killed by SIGKILL at frame 3."""
    knit_blender.register()
    cloth = make_animated_grid()
    select(cloth)
    bpy.ops.object.knit_apply(pattern="stockinette", repeats=(4, 4))
    select(bpy.data.objects[f"{cloth.name}.knit"])
    bpy.app.handlers.frame_change_post.append(
        lambda scene, *_: os.kill(os.getpid(), signal.SIGKILL) if scene.frame_current == 3 else None)
    bpy.ops.object.knit_bake_pc2(filepath=os.path.join(folder, "c.pc2"), frame_start=1, frame_end=6)


def killed_bake(folder, knit_obj):
    killed = os.path.join(folder, "killed")
    os.mkdir(killed)
    child = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", "--python", os.path.abspath(__file__),
                            "--", "bake-and-die", killed], capture_output=True, text=True, timeout=120)
    left = os.listdir(killed)
    check(child.returncode == -signal.SIGKILL, f"the child Blender was killed mid-bake ({child.returncode})")
    check(len(left) == 1 and re.fullmatch(r"\.c\.pc2\.[0-9]+\.0\.tmp", left[0]) is not None,
          f"a killed bake leaves only a hidden .c.pc2.PID.N.tmp ({left})")
    # The next bake into the folder removes it (it used to wait for another knit write there).
    select(knit_obj)
    check(bpy.ops.object.knit_bake_pc2(filepath=os.path.join(killed, "c.pc2"), frame_start=1, frame_end=2) ==
          {"FINISHED"}, "the bake after the killed one finished")
    check(os.listdir(killed) == ["c.pc2"], f"the next bake into the folder removed it ({os.listdir(killed)})")


if sys.argv[-2:-1] == ["bake-and-die"]:
    bake_and_die(sys.argv[-1])
else:
    main()
