# export_scene: formats by extension, stats, errors.
import os
import subprocess

import pytest

import knit


@pytest.fixture(scope="module")
def scene():
    return knit.build_scene("stockinette", "plane", repeats=(3, 3))


@pytest.mark.parametrize("name", ["plies.obj", "plies.glb", "yarns.ply"])
def test_export_writes_the_file_and_reports_its_size(scene, tmp_path, name):
    path = str(tmp_path / name)
    stats = knit.export_scene(scene, path, what=name.split(".")[0])
    assert os.path.getsize(path) == stats["bytes"] > 0
    assert stats["format"] == name.split(".")[1] and stats["curves"] > 0


def test_export_tubes_counts_triangles(scene, tmp_path):
    stats = knit.export_scene(scene, str(tmp_path / "t.glb"), what="tubes", sides=6)
    assert stats["triangles"] > 0


def test_export_unknown_extension_raises_and_writes_nothing(scene, tmp_path):
    path = tmp_path / "x.unknown"
    with pytest.raises(knit.Error):
        knit.export_scene(scene, str(path))
    assert not path.exists()


def test_export_unknown_what_names_the_argument(scene, tmp_path):
    with pytest.raises(knit.Error, match="what: expected"):
        knit.export_scene(scene, str(tmp_path / "x.obj"), what="ropes")


def test_export_meshopt_tubes_are_smaller_than_plain_ones(scene, tmp_path):
    plain = knit.export_scene(scene, str(tmp_path / "plain.glb"), what="tubes")
    packed = knit.export_scene(scene, str(tmp_path / "packed.glb"), what="tubes", quantize=True, meshopt=True)
    assert packed["vertices"] == plain["vertices"]
    assert packed["bytes"] < 0.5 * plain["bytes"]


def test_export_over_the_memory_budget_raises_and_writes_nothing(scene, tmp_path):
    path = tmp_path / "t.glb"
    with pytest.raises(knit.Error, match=r"over the memory budget \(max_memory\)") as e:
        knit.export_scene(scene, str(path), what="tubes", max_memory="1K")
    assert "--" not in str(e.value)
    assert not path.exists()
    with pytest.raises(knit.Error, match=r"the memory budget \(max_memory\) 'lots'"):
        knit.export_scene(scene, str(tmp_path / "x.obj"), max_memory="lots")


def test_export_errors_name_the_keywords_not_cli_flags(scene, tmp_path):
    # The library names settings in words; export_scene adds its keyword after the first mention.
    with pytest.raises(knit.Error) as e:
        knit.export_scene(scene, str(tmp_path / "c.glb"), what="plies", draco=True)
    message = str(e.value)
    assert "Draco compression (draco) applies to tube meshes only" in message
    assert "what to export (what) is plies" in message
    assert "--" not in message
    with pytest.raises(knit.Error, match=r"the number of tube sides \(sides\) must be in \[3, 1024\], got 2"):
        knit.export_scene(scene, str(tmp_path / "t.obj"), what="tubes", sides=2)


def test_export_of_an_empty_result_raises_and_writes_nothing(tmp_path):
    # No pattern period fits the mesh: no yarn lands on it. Refused by the library, as by the CLI.
    empty = knit.build_scene("stockinette", "plane", repeats=(1e-6, 1e-6))
    for name in ["e.obj", "e.glb", "e.bcc"]:
        path = tmp_path / name
        with pytest.raises(knit.Error, match="nothing to export: no yarn of pattern 'stockinette' lands on mesh"):
            knit.export_scene(empty, str(path), what="yarns")
        assert not path.exists()
    assert list(tmp_path.iterdir()) == []


def test_remove_stale_temporaries_removes_only_those_of_dead_processes(tmp_path):
    gone = subprocess.Popen(["true"])
    gone.wait()  # its pid names no process now
    dead = tmp_path / f".c.pc2.{gone.pid}.0.tmp"
    staging = tmp_path / f".knit-staging.{gone.pid}.3.tmp"
    alive = tmp_path / f".d.pc2.{os.getpid()}.0.tmp"
    for f in (dead, alive):
        f.write_bytes(b"partial")
    staging.mkdir()
    (staging / "x.obj").write_text("v 0 0 0\n")
    (tmp_path / "keep.obj").write_text("v 0 0 0\n")
    assert knit.remove_stale_temporaries(str(tmp_path)) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([alive.name, "keep.obj"])
    assert knit.remove_stale_temporaries(str(tmp_path / "missing")) == 0  # never raises
