#!/usr/bin/env python3
"""Hostile-input hunt over the Python module's keyword arguments and files (issue 29), beyond the
array checks of python/tests/test_hostile_arrays.py. Each call runs in a child process (a crash or a
hang ends only that case) in a fresh folder. MISHANDLED: a signal or timeout, a peak above 2 GB,
an exception other than knit.Error / ValueError / TypeError / OSError (or knit.Error's message
naming a CLI flag "--x" or a library internal), a non-finite array returned, a file left behind
after a refusal or a changed input.

    PYTHONPATH=build/python /usr/bin/python3 tools/hostile_python.py [--only SUBSTRING]
"""
import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile

PRELUDE = r'''
import os, sys, math, numpy as np, knit
def finite(x):
    for name in ("points", "normals", "radial", "positions", "uvs", "data"):
        a = getattr(x, name, None)
        if a is not None and not np.all(np.isfinite(np.asarray(a))):
            raise SystemExit("NONFINITE " + name)
    if isinstance(x, dict):
        for k, v in x.items():
            if isinstance(v, float) and not math.isfinite(v):
                raise SystemExit("NONFINITE " + k)
    return x
def frames_of(count=2):
    """s_0001.obj ... copies of plane.obj (the bound scene's own mesh file), for knit.distributed (set up by
    the case, so not counted as left behind); returns that scene."""
    for k in range(1, count + 1):
        open("s_%04d.obj" % k, "w").write(open("plane.obj").read())
    return knit.build_scene("stockinette", "plane.obj", repeats=(2, 2))
def small(**kw):
    a = dict(repeats=(2, 2), res_u=2, res_v=2)
    a.update(kw)
    return knit.build_scene("stockinette", "plane", **a)
'''

NUMS = ["0", "-1", "1e308", "float('nan')", "float('inf')", "10**30", "'3'", "None", "True", "[]"]


def cases():
    c = []
    add = lambda name, code: c.append((name, code))
    for kw in ["plies", "ply_pitch", "ply_radius", "center_radius", "samples_per_turn", "clamp_tolerance",
               "weld_tolerance"]:
        for v in NUMS:
            add(f"build_scene {kw}={v}", f"finite(small({kw}={v}).plies)")
    for kw in ["res_u", "res_v"]:
        for v in ["0", "-1", "10**9", "2**40", "float('nan')", "'a'"]:
            add(f"build_scene {kw}={v}", f"finite(small({kw}={v}).yarns)")
    for v in ["(0, 0)", "(-1, 2)", "(1e9, 1e9)", "(float('nan'), 1)", "(1,)", "(1, 2, 3)", "'ab'", "(1e-300, 1e-300)"]:
        add(f"build_scene repeats={v}", f"finite(small(repeats={v}).yarns)")
    for v in ["'X'", "''", "None", "1"]:
        add(f"build_scene twist={v}", f"small(twist={v})")
    for v in ["'-1G'", "'0'", "'nanG'", "'1e308G'", "'5X'", "1", "'0.0001K'"]:
        add(f"build_scene max_memory={v}", f"finite(small(max_memory={v}).yarns)")
    for v in ["'bogus'", "'strain'"]:
        add(f"build_scene deform={v}", f"finite(small(deform={v}).yarns)")
    add("build_scene strain_table=garbage", "small(strain_table='garbage.npy')")
    add("build_scene strain_table=dir", "small(strain_table='adir')")
    for p in ["'empty.pyp'", "'garbage.pyp'", "'adir'", "'missing.pyp'", "''", "'/dev/zero'", "b'x'", "3"]:
        add(f"load_pattern {p}", f"knit.load_pattern({p})")
    for m in ["'empty.obj'", "'garbage.obj'", "'adir'", "'missing.obj'", "'/dev/zero'", "'garbage.glb'"]:
        add(f"load_mesh {m}", f"knit.load_mesh({m})")
    for v in ["(0, 5)", "(-1, 5)", "(5000, 5000)", "(2**31, 2)"]:
        add(f"load_mesh plane res={v}", f"finite(knit.load_mesh('plane', *{v}))")
    for t in ["''", "'k k\\nk'", "'zz'", "'k' * 100000", "'\\x00\\xff'"]:
        add(f"chart_pattern {t[:20]}", f"finite(knit.chart_pattern({t}))")
    for r in ["0", "-1", "float('nan')", "1e308", "1e-300"]:
        add(f"chart_pattern yarn_radius={r}", f"finite(knit.chart_pattern('k k\\nk k\\n', yarn_radius={r}))")
    add("chart_floats max_float=-1", "knit.chart_floats('k k\\nk k\\n', max_float=-1)")
    # make_plies
    for kw, v in [("yarn_radius", "0"), ("yarn_radius", "float('nan')"), ("yarn_radius", "1e308"), ("count", "0"),
                  ("count", "100"), ("pitch", "-1"), ("pitch", "1e-12"), ("samples_per_turn", "10**6"),
                  ("twist", "'Q'")]:
        args = dict(yarn_radius="s.yarn_radius")
        args[kw] = v
        call = ", ".join(f"{k}={w}" for k, w in args.items())
        add(f"make_plies {kw}={v}", f"s = small(build_plies=False); finite(knit.make_plies(s.yarns, {call}))")
    # export_scene
    for path in ["'adir'", "'missing/o.obj'", "'o.xyz'", "''"]:
        add(f"export_scene path={path}", f"s = small(); knit.export_scene(s, {path})")
    for kw, v in [("what", "'nope'"), ("sides", "2"), ("sides", "10**9"), ("draco", "'yes'"),
                  ("max_memory", "'1K'")]:
        add(f"export_scene {kw}={v}", f"s = small(); knit.export_scene(s, 'o.glb', {kw}={v})")
    add("export_scene over the pattern file", "s = knit.build_scene('p.pyp', 'plane', repeats=(2, 2), res_u=2, "
        "res_v=2); knit.export_scene(s, 'p.pyp')")
    add("export_scene over the mesh file", "s = knit.build_scene('p.pyp', 'plane.obj', repeats=(2, 2)); "
        "knit.export_scene(s, './plane.obj', what='yarns')")
    add("save_bound_scene over the mesh file", "s = knit.build_scene('p.pyp', 'plane.obj', repeats=(2, 2)); "
        "knit.save_bound_scene(s, 'plane.obj')")
    add("export_scene what=tubes draco+quantize", "s = small(); knit.export_scene(s, 'o.glb', what='tubes', "
        "draco=True, quantize=True)")
    # strain tables
    for kw, v in [("samples", "(0, 1, 1)"), ("samples", "(100, 100, 100)"), ("sx_range", "(1, 0)"),
                  ("sx_range", "(0, 0)"), ("sa_range", "(float('nan'), 1)"), ("iterations", "0"),
                  ("iterations", "-5")]:
        add(f"strain_table {kw}={v}", f"finite(knit.strain_table('stockinette', samples=(2, 2, 2), iterations=5, "
            f"**{{'{kw}': {v}}}))" if kw != "samples" else f"finite(knit.strain_table('stockinette', {kw}={v}, "
            "iterations=5))")
    add("strain_table path over its pattern", "knit.strain_table('p.pyp', path='p.pyp', samples=(2, 2, 2), "
        "iterations=5)")
    add("strain_table path=dir", "knit.strain_table('stockinette', path='adir', samples=(2, 2, 2), iterations=5)")
    for f in ["'garbage.npy'", "'adir'", "'missing.npy'", "'empty.npy'"]:
        add(f"load_strain_table {f}", f"knit.load_strain_table({f})")
    # bound scenes
    for f in ["'garbage.knitbind'", "'empty.knitbind'", "'adir'", "'missing.knitbind'"]:
        add(f"load_bound_scene {f}", f"knit.load_bound_scene({f})")
    add("save_bound_scene to a folder", "knit.save_bound_scene(small(), 'adir')")
    add("save_bound_scene over the pattern", "s = knit.build_scene('p.pyp', 'plane', repeats=(2, 2), res_u=2, "
        "res_v=2); knit.save_bound_scene(s, 'p.pyp')")
    add("load_bound_scene max_memory=-1", "knit.save_bound_scene(small(), 'b.knitbind'); "
        "knit.load_bound_scene('b.knitbind', max_memory='-1')")
    # frame numbers
    for args in ["'f_%d%d.obj'", "'f_%s.obj'", "'f_%n.obj'", "'missing/f_%04d.obj'", "'f_%04d.obj', step=0",
                 "'f_%04d.obj', first=5, last=1", "'f_%04d.obj', last=-5", "'adir'"]:
        add(f"frame_numbers {args}", f"knit.frame_numbers({args})")
    # evaluate on a scene: deform keyword
    add("Scene.evaluate deform='bogus'", "s = small(); s.evaluate(s.mesh.positions, deform='bogus')")
    add("spell_settings bad spellings", "knit.spell_settings('the ply pitch', [('a',)])")
    return c


def fresh_cases():
    """Round 4 of the hunt (issue 29): the functions, keywords and files rounds 1-3 did not try."""
    c = []
    add = lambda name, code: c.append((name, code))
    # Mesh files: concave faces per format, NaN / zero UVs, absurd sizes.
    for f in ["concave.obj", "concave.off", "concave.ply", "uv_nan.obj", "uv_zero.obj", "huge.off", "mesh.stl",
              "tiny.obj"]:
        add(f"load_mesh {f}", f"m = knit.load_mesh('{f}'); finite(m); knit.uv_to_metre_scale(m)")
        add(f"build_scene mesh={f}", f"finite(knit.build_scene('stockinette', '{f}', repeats=(2, 2)).plies)")
    add("build_scene huge.off at physical size", "finite(knit.build_scene('stockinette', 'huge.off').plies)")
    add("uv_to_metre_scale all-zero UVs", "m = knit.Mesh(np.eye(3), [[0, 1, 2]], np.zeros((3, 2))); "
        "r = knit.uv_to_metre_scale(m); assert all(math.isfinite(v) for v in r), r")
    add("uv_to_metre_scale of 3", "knit.uv_to_metre_scale(3)")
    add("Mesh without faces", "m = knit.Mesh(np.eye(3), np.zeros((0, 3), np.uint32), np.zeros((3, 2))); "
        "finite(knit.build_scene('stockinette', m, repeats=(2, 2)).yarns)")
    add("build_scene mesh=Mesh without uvs", "m = knit.Mesh(np.eye(3), [[0, 1, 2]]); "
        "finite(knit.build_scene('stockinette', m, repeats=(2, 2)).yarns)")
    add("build_scene pattern=3", "knit.build_scene(3, 'plane')")
    add("build_scene mesh=None", "knit.build_scene('stockinette', None)")
    add("build_scene pattern=a Mesh", "knit.build_scene(knit.load_mesh('plane', 2, 2), 'plane')")
    # Charts: odd bytes and names.
    for t in ["'k k\\r\\nk k\\r\\n'", "'k\\tk\\nk\\tk\\n'", "'k k\\x00\\nk k\\n'", "'\\n\\n  \\n'",
              "'k \\u00e9\\nk k\\n'", "b'k k\\nk k\\n'", "None"]:
        add(f"chart_pattern {t[:24]}", f"finite(knit.chart_pattern({t}))")
    add("chart_pattern name=NUL", "finite(knit.chart_pattern('k k\\nk k\\n', name='a\\x00b'))")
    add("chart_pattern name='x' * 100000", "knit.chart_pattern('zz', name='x' * 100000)")
    for v in ["10**9", "2**40", "float('nan')", "'5'", "0"]:
        add(f"chart_floats max_float={v}", f"knit.chart_floats('k k\\nk k\\n', max_float={v})")
    # make_plies: the keywords rounds 1-3 left.
    for kw, v in [("ply_radius", "float('nan')"), ("ply_radius", "-1"), ("ply_radius", "1e308"),
                  ("center_radius", "float('inf')"), ("center_radius", "-1"), ("samples_per_turn", "0"),
                  ("samples_per_turn", "-3"), ("pitch", "float('nan')"), ("count", "-1"), ("count", "2**40"),
                  ("yarn_radius", "-1"), ("yarn_radius", "'a'")]:
        add(f"make_plies {kw}={v}", f"s = small(build_plies=False); finite(knit.make_plies(s.yarns, "
            f"**{{'yarn_radius': s.yarn_radius, '{kw}': {v}}}))")
    add("make_plies yarns=3", "knit.make_plies(3, 0.001)")
    add("make_plies yarns=plies", "s = small(); finite(knit.make_plies(s.plies, s.yarn_radius))")
    # export_scene: formats and keywords rounds 1-3 left.
    for path, kw in [("'o.bcc'", ""), ("'o.pbrt'", ""), ("'o.ply'", ""), ("'o.GLB'", ""), ("'o'", ""),
                     ("'o.glb'", "what='TUBES'"), ("'o.glb'", "sides=1025"), ("'o.glb'", "sides=-1"),
                     ("'o.glb'", "what='tubes', meshopt=True, draco=True"), ("'o.obj'", "what='tubes', draco=True"),
                     ("'o.glb'", "max_memory='nan'"), ("'o.glb'", "caps='no'"), ("b'o.glb'", ""), ("3", ""),
                     ("'o.glb'", "yarn_colors=True")]:
        add(f"export_scene {path} {kw}", f"s = small(); finite(knit.export_scene(s, {path}{', ' if kw else ''}{kw}))")
    add("export_scene scene=3", "knit.export_scene(3, 'o.glb')")
    # Strain tables: saving, keyword types.
    for path in ["'adir'", "'missing/t.npy'", "''", "'t.txt'", "'p.pyp'"]:
        add(f"StrainTable.save {path} (table of p.pyp)", "t = knit.strain_table('p.pyp', samples=(2, 2, 2), "
            f"iterations=5); t.save({path})")
    for kw, v in [("samples", "(2, 2)"), ("samples", "'abc'"), ("samples", "(2.5, 2, 2)"), ("iterations", "10**12"),
                  ("sx_range", "(0, float('inf'))"), ("sy_range", "'ab'"), ("pattern", "3")]:
        add(f"strain_table {kw}={v}", f"finite(knit.strain_table(**{{'samples': (2, 2, 2), 'iterations': 5, "
            f"'{kw}': {v}}}))")
    add("build_scene strain_table of another pattern", "t = knit.strain_table('stockinette', samples=(2, 2, 2), "
        "iterations=5); finite(knit.build_scene('p.pyp', 'plane', repeats=(2, 2), res_u=2, res_v=2, "
        "deform='strain', strain_table=t).yarns)")
    add("build_scene strain_table=3", "small(strain_table=3)")
    # Bound scenes: other files, settings text.
    for f in ["'p.pyp'", "'plane.obj'", "''", "3"]:
        add(f"load_bound_scene {f}", f"knit.load_bound_scene({f})")
    for v in ["'x' * 10**6", "'a\\x00b'", "3", "'{\"repeats\": 5}'"]:
        add(f"save_bound_scene settings={v[:16]}", f"s = small(); knit.save_bound_scene(s, 'b.knitbind', "
            f"settings={v}); s2 = knit.load_bound_scene('b.knitbind'); finite(s2.yarns)")
    add("save_bound_scene to ''", "knit.save_bound_scene(small(), '')")
    # frame_numbers and stale temporaries.
    for args in ["'f_%04d.obj', first=2**40", "'f_%04d.obj', step=2**63", "'f_%04d.obj', first='a'", "3",
                 "'f_%04d.obj', first=float('nan')"]:
        add(f"frame_numbers {args}", f"knit.frame_numbers({args})")
    for f in ["'missing'", "'plane.obj'", "''", "3"]:
        add(f"remove_stale_temporaries {f}", f"knit.remove_stale_temporaries({f})")
    add("spell_settings non-pairs", "knit.spell_settings('x (a)', [('a', 'b', 'c')])")
    add("spell_settings of 3", "knit.spell_settings(3, [])")
    # Scene: evaluate with bad keywords, and many threads at once with one hostile pose among them.
    add("Scene.evaluate deform='strain' without a table", "s = small(); s.evaluate(s.mesh.positions, deform='strain')")
    add("Scene.evaluate deform=3", "s = small(); s.evaluate(s.mesh.positions, deform=3)")
    add("Scene.evaluate_plies of a scene without plies", "s = small(build_plies=False); "
        "finite(s.evaluate_plies(s.mesh.positions))")
    add("Scene.evaluate 8 threads, one NaN pose", """import threading
    s = small(); p = s.mesh.positions; want = s.evaluate_plies(p + 0.01).points; errs = []; outs = []
    def good():
        for _ in range(20): outs.append(np.array_equal(s.evaluate_plies(p + 0.01).points, want))
    def bad():
        q = p.copy(); q[0, 0] = float('nan')
        for _ in range(20):
            try: s.evaluate_plies(q); errs.append('accepted')
            except knit.Error as e: errs.append(str(e))
    ts = [threading.Thread(target=good) for _ in range(6)] + [threading.Thread(target=bad) for _ in range(2)]
    [t.start() for t in ts]; [t.join() for t in ts]
    assert all(outs) and len(outs) == 120, 'a concurrent result differs'
    assert all(e != 'accepted' for e in errs) and len(errs) == 40, errs[:2]""")
    add("Scene.evaluate while another thread loads a bound scene", """import threading
    s = small(); knit.save_bound_scene(s, 'b.knitbind'); out = []
    def ev():
        for _ in range(20): out.append(finite(s.evaluate(s.mesh.positions)))
    def ld():
        for _ in range(5): finite(knit.load_bound_scene('b.knitbind').yarns)
    ts = [threading.Thread(target=ev) for _ in range(3)] + [threading.Thread(target=ld)]
    [t.start() for t in ts]; [t.join() for t in ts]
    assert len(out) == 60""")
    # knit.distributed: arguments checked before a cluster starts.
    for kw in ["fps=float('nan')", "fps=0", "threads=0", "export='nope'", "first=5, last=1", "chunk=2**70"]:
        add(f"distributed.bake {kw}", "import knit.distributed as d; knit.save_bound_scene(frames_of(), 'b.knitbind'); "
            f"d.bake('b.knitbind', 's_%04d.obj', 'o.pc2', knit_cli=os.environ['KNIT_CLI'], {kw})")
    add("distributed.render_frames render_args='x' (a str)", "import knit.distributed as d; "
        "knit.save_bound_scene(small(), 'b.knitbind'); d.render_frames('b.knitbind', 'f_%04d.obj', 'r_%04d.png', "
        "knit_cli=os.environ['KNIT_CLI'], render_args='x')")
    return c


def run_case(folder_template, code, timeout):
    folder = tempfile.mkdtemp(prefix="hostile-py-")
    shutil.rmtree(folder)
    shutil.copytree(folder_template, folder)
    before = {f: open(os.path.join(folder, f), "rb").read() for f in os.listdir(folder)
              if os.path.isfile(os.path.join(folder, f))}
    script = PRELUDE + f"""
try:
    {code}
    print("RESULT ok")
except (knit.Error, ValueError, TypeError, OSError) as e:
    print("RESULT refused " + type(e).__name__ + ": " + str(e).replace(chr(10), ' '))
except BaseException as e:
    if isinstance(e, SystemExit): raise
    print("RESULT other " + type(e).__name__ + ": " + str(e).replace(chr(10), ' '))
"""
    limit = lambda: resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))
    try:
        p = subprocess.run([sys.executable, "-c", script], cwd=folder, capture_output=True, text=True,
                           timeout=timeout, preexec_fn=limit)
        out, rc = p.stdout + p.stderr, p.returncode
    except subprocess.TimeoutExpired:
        out, rc = "", None
    usage = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024
    after = {f for f in os.listdir(folder)}
    new = sorted(after - set(os.listdir(folder_template)))
    changed = sorted(f for f, data in before.items()
                     if not os.path.isfile(os.path.join(folder, f)) or open(os.path.join(folder, f), "rb").read() != data)
    shutil.rmtree(folder, ignore_errors=True)
    why = []
    if rc is None:
        why.append("hang (timeout)")
    elif rc != 0 and "NONFINITE" not in out:
        why.append(f"exit {rc} (crash or uncaught): {out.strip().splitlines()[-1] if out.strip() else ''}")
    if "NONFINITE" in out:
        why.append("non-finite result " + out.split("NONFINITE", 1)[1].split()[0])
    m = re.search(r"RESULT (\w+) ?(.*)", out)
    kind, msg = (m.group(1), m.group(2)) if m else ("?", "")
    if kind == "other":
        why.append("raised " + msg[:80])
    if kind == "refused":
        if re.search(r"(?<![\w-])--[a-z]", msg):
            why.append("names a CLI flag")
        if re.search(r"::|\b[A-Z][A-Za-z]*Options\.|\bstd\b", msg):
            why.append("names an internal")
        left = [f for f in new if f != "b.knitbind" and not re.fullmatch(r"s_\d{4}\.obj", f)]
        if left:
            why.append("refused but left " + ",".join(left))
    if [f for f in new if ".tmp" in f or "knit-staging" in f]:
        why.append("temporary left")
    if changed:
        why.append("changed " + ",".join(changed))
    return kind, msg, why, usage


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default="")
    ap.add_argument("--fresh", action="store_true", help="only the cases of round 4 (fresh_cases)")
    ap.add_argument("--timeout", type=int, default=60)
    a = ap.parse_args()
    import knit  # fails early when PYTHONPATH lacks build/python
    # knit.distributed runs the command line: the one built beside the module.
    os.environ.setdefault("KNIT_CLI", os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(knit.__file__)))), "apps", "knit", "knit"))
    # The children run in other folders: the module's folder as an absolute path.
    os.environ["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.dirname(os.path.abspath(knit.__file__))),
                                                os.environ.get("PYTHONPATH", "")])
    template = tempfile.mkdtemp(prefix="hostile-py-fixtures-")
    try:
        rnd = bytes((i * 7919 + 13) % 256 for i in range(4096))
        for ext in ["pyp", "obj", "glb", "npy", "knitbind"]:
            open(os.path.join(template, f"empty.{ext}"), "wb").close()
            open(os.path.join(template, f"garbage.{ext}"), "wb").write(rnd)
        os.mkdir(os.path.join(template, "adir"))
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        from hostile_cli import l_hexagon
        from grid_obj import grid_obj
        w = lambda name, data: open(os.path.join(template, name), "wb" if isinstance(data, bytes) else "w").write(data)
        for fmt in ["obj", "off", "ply"]:
            w(f"concave.{fmt}", l_hexagon(fmt))
        w("uv_nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
        w("uv_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n")
        w("huge.off", "STOFF\n4 2 0\n0 0 0 0 0\n1e30 0 0 1 0\n1e30 1e30 0 1 1\n0 1e30 0 0 1\n3 0 1 2\n3 0 2 3\n")
        w("mesh.stl", grid_obj())
        w("tiny.obj", grid_obj(size=1e-30))
        for k in range(1, 3):  # frames of small()'s 2 x 2 plane
            w(f"f_{k:04d}.obj", grid_obj(n=2))
        subprocess.run([sys.executable, "-c", "import knit, shutil, os\n"
                        "open('plane.obj', 'w').write('v 0 0 0\\nv 1 0 0\\nv 1 1 0\\nv 0 1 0\\nvt 0 0\\nvt 1 0\\n"
                        "vt 1 1\\nvt 0 1\\nf 1/1 2/2 3/3\\nf 1/1 3/3 4/4\\n')\n"
                        "open('p.pyp', 'w').write(open(os.environ['KNIT_PATTERN']).read())"],
                       cwd=template, check=True, env={**os.environ, "KNIT_PATTERN": os.path.join(
                           os.path.dirname(os.path.abspath(__file__)), "..", "patterns",
                           sorted(f for f in os.listdir(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                                     "..", "patterns")) if f.endswith(".pyp"))[0])})
        bad = 0
        todo = [c for c in (fresh_cases() if a.fresh else cases() + fresh_cases()) if a.only in c[0]]
        print(f"{'case':60} {'result':8}  verdict")
        for name, code in todo:
            kind, msg, why, _ = run_case(template, code, a.timeout)
            bad += bool(why)
            print(f"{name[:60]:60} {kind:8}  {'ok' if not why else 'MISHANDLED: ' + '; '.join(why)}", flush=True)
            if why or kind == "refused":
                print(f"{'':60}   {msg[:160]}", flush=True)
        print(f"\n{len(todo)} hostile calls, {bad} mishandled")
        return 1 if bad else 0
    finally:
        shutil.rmtree(template, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
