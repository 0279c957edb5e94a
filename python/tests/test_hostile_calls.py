# Keyword arguments and paths a hostile caller gives (issue 29; found by tools/hostile_python.py,
# which runs the whole hunt): a call that would write over a file it reads is refused naming the
# keyword and the file (the command line refuses the same with its flags), and a strain range of
# one value over several samples names its keyword.
import os
import shutil

import pytest

import knit

PATTERN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "patterns", "stockinette.pyp")


def plane_obj(path):
    lines = [f"v {i / 2} {j / 2} 0" for j in range(3) for i in range(3)]
    lines += [f"vt {i / 2} {j / 2}" for j in range(3) for i in range(3)]
    for j in range(2):
        for i in range(2):
            a = j * 3 + i + 1
            lines += [f"f {a}/{a} {a + 1}/{a + 1} {a + 4}/{a + 4}", f"f {a}/{a} {a + 4}/{a + 4} {a + 3}/{a + 3}"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


@pytest.fixture
def inputs(tmp_path):
    shutil.copy(PATTERN, tmp_path / "p.pyp")
    plane_obj(tmp_path / "m.obj")
    return tmp_path


def unchanged(folder, before):
    return {f: (folder / f).read_bytes() for f in os.listdir(folder)} == before


def test_writing_over_the_scenes_own_pattern_or_mesh_file_is_refused(inputs, monkeypatch):
    monkeypatch.chdir(inputs)
    scene = knit.build_scene("p.pyp", "m.obj", repeats=(2, 2))
    before = {f: (inputs / f).read_bytes() for f in os.listdir(inputs)}
    with pytest.raises(knit.Error, match=r"path '\./m\.obj' is the scene's mesh file \('m\.obj'\)"):
        knit.export_scene(scene, "./m.obj", what="yarns")
    with pytest.raises(knit.Error, match=r"path 'sub/\.\./p\.pyp' is the scene's pattern file"):
        os.mkdir("sub")
        knit.save_bound_scene(scene, "sub/../p.pyp")
    with pytest.raises(knit.Error, match=r"path 'p\.pyp' is the pattern file"):
        knit.strain_table("p.pyp", path="p.pyp", samples=(2, 2, 2), iterations=5)
    os.rmdir("sub")
    assert unchanged(inputs, before)
    knit.export_scene(scene, "out.obj", what="yarns")  # another path is written as before
    assert os.path.getsize("out.obj") > 0


def test_a_one_value_strain_range_over_several_samples_names_its_keyword():
    # The axes of such a table do not increase: no reader accepts it.
    with pytest.raises(knit.Error, match=r"the sx range \(sx_range\) 0 0 must be increasing"):
        knit.strain_table("stockinette", samples=(2, 2, 2), sx_range=(0, 0), iterations=5)
    table = knit.strain_table("stockinette", samples=(1, 2, 2), sx_range=(0, 0), iterations=5)
    assert table.axes[0] == [0.0]


def test_arguments_of_the_wrong_type_raise_type_error_naming_the_keyword(inputs, monkeypatch):
    # pybind11's cast of a pattern / mesh / strain table / deform of another type raised
    # RuntimeError("Unable to cast Python instance to C++ type ..."), naming no keyword.
    monkeypatch.chdir(inputs)
    mesh = knit.load_mesh("plane", 2, 2)
    cases = [(lambda: knit.build_scene(3, "plane", repeats=(2, 2), res_u=2, res_v=2), "pattern: expected"),
             (lambda: knit.build_scene(mesh, "plane", repeats=(2, 2), res_u=2, res_v=2), "got Mesh"),
             (lambda: knit.build_scene("p.pyp", 3, repeats=(2, 2)), "mesh: expected"),
             (lambda: knit.build_scene("p.pyp", "m.obj", repeats=(2, 2), strain_table=3), "strain_table: expected"),
             (lambda: knit.strain_table(3, samples=(2, 2, 2), iterations=5), "pattern: expected"),
             (lambda: knit.strain_table("p.pyp", path=3, samples=(2, 2, 2), iterations=5), "path: expected")]
    for call, words in cases:
        with pytest.raises(TypeError, match=words):
            call()
    scene = knit.build_scene("p.pyp", "m.obj", repeats=(2, 2))
    with pytest.raises(TypeError, match="deform: expected None, 'none' or 'strain', got int"):
        scene.evaluate(scene.mesh.positions, deform=3)


def test_bake_settings_are_named_by_their_keyword_before_a_cluster_starts(inputs, monkeypatch):
    # fps / threads / export went to `knit animate` unchecked: after a cluster started, a chunk failed
    # naming --fps (a flag the Python caller never typed), or the missing dask module was reported first.
    import knit.distributed as d
    monkeypatch.chdir(inputs)
    open("b.knitbind", "wb").write(b"not checked before the settings")
    for kw, words in [({"fps": float("nan")}, "fps: must be a frame rate"), ({"fps": 0}, "fps: "),
                      ({"threads": -1}, "threads: "), ({"export": "tubes"}, "export: must be 'plies' or 'yarns'")]:
        with pytest.raises(knit.Error, match=words) as e:
            d.bake("b.knitbind", "f_%04d.obj", "o.pc2", knit_cli="/nonexistent/knit", **kw)
        assert "--" not in str(e.value)


def test_saving_a_strain_table_over_its_pattern_file_is_refused(inputs, monkeypatch):
    monkeypatch.chdir(inputs)
    table = knit.strain_table("p.pyp", samples=(2, 2, 2), iterations=5)
    before = (inputs / "p.pyp").read_bytes()
    with pytest.raises(knit.Error, match="path"):
        table.save("./p.pyp")
    assert (inputs / "p.pyp").read_bytes() == before
    table.save("t.npy")
    knit.load_strain_table("t.npy").save("t.npy")  # a loaded table may be written over its own file


def test_render_args_given_as_one_string_is_refused(inputs, monkeypatch):
    # The string was iterated character by character into `knit render` arguments.
    import knit.distributed as d
    monkeypatch.chdir(inputs)
    open("b.knitbind", "wb").write(b"x")
    with pytest.raises(TypeError, match="render_args: expected a list"):
        d.render_frames("b.knitbind", "f_%04d.obj", "r_%04d.png", knit_cli="/nonexistent/knit", render_args="--spp 4")
