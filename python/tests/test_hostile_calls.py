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
