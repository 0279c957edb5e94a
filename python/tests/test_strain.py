"""knit.strain_table / load_strain_table and strain-aware evaluation (docs/deformation.md)."""
import numpy as np
import pytest

import knit


@pytest.fixture(scope="module")
def table():
    return knit.strain_table(samples=(3, 2, 3), sx_range=(0.0, 0.6), sa_range=(-0.1, 0.1), sy_range=(-0.1, 0.1))


def test_table_layout_and_round_trip(table, tmp_path):
    assert table.vertex_count == 24
    assert [len(a) for a in table.axes] == [3, 2, 3]
    assert table.data.shape == (24 * 18, 4)
    path = str(tmp_path / "t.npy")
    table.save(path)
    back = knit.load_strain_table(path)
    assert np.array_equal(back.data, table.data)
    assert np.array_equal(np.load(path), table.data)  # plain numpy reads it


def square(n=8, size=0.05):
    """A square in the xy plane with uv = position / size: isometric at the pattern's own size."""
    ij = np.stack(np.meshgrid(np.arange(n + 1), np.arange(n + 1)), -1).reshape(-1, 2)
    uv = ij / n
    positions = np.column_stack([uv * size, np.zeros(len(uv))])
    idx = lambda i, j: j * (n + 1) + i  # noqa: E731
    faces = []
    for j in range(n):
        for i in range(n):
            faces += [[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)], [idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]]
    faces = np.array(faces)
    return knit.Mesh(positions, faces, uvs=uv, face_uvs=faces)


def test_evaluate_deform_modes(table):
    scene = knit.build_scene("stockinette", square(), build_plies=False, strain_table=table)
    rest = np.array(scene.mesh.positions)
    # A stretch along the courses (x): the table slides the yarns.
    pose = rest * np.array([1.4, 1.0, 1.0])
    strained = scene.evaluate(pose)
    geometric = scene.evaluate(pose, deform="none")
    assert strained.points.shape == geometric.points.shape
    assert np.abs(strained.points - geometric.points).max() > 0.1 * scene.yarn_radius
    # At rest (isometric layout) the strain is zero: the same points.
    assert np.array_equal(scene.evaluate(rest).points, scene.evaluate(rest, deform="none").points)
    plain = knit.build_scene("stockinette", square(), build_plies=False, deform="none")
    assert plain.stats["deform"] == "none" and plain.stats["deform_why"] == "deform='none'"
    with pytest.raises(knit.Error, match="strain table"):
        plain.evaluate(pose, deform="strain")
    with pytest.raises(knit.Error, match="deform"):
        plain.evaluate(pose, deform="sideways")


def test_default_deform_is_strain_for_the_default_pattern(tmp_path, monkeypatch):
    """deform='' (the default): the default pattern's table is made in seconds, so strain; it is
    cached, and the next scene reads it with the same result."""
    monkeypatch.setenv("KNIT_CACHE_DIR", str(tmp_path))
    before = knit.strain_table_at_hand("stockinette")  # what a front end asks before a long wait
    assert not before["cached"] and before["quick"] and before["seconds"] > 0, before
    first = knit.build_scene("stockinette", square(), build_plies=False)
    assert first.stats["deform"] == "strain"
    assert "made now" in first.stats["deform_why"]
    assert knit.strain_table_at_hand("stockinette") == {"cached": True, "quick": True, "seconds": 0.0}
    second = knit.build_scene("stockinette", square(), build_plies=False)
    assert second.stats["deform_why"] == "the pattern's strain table was in the cache"
    rest = np.array(first.mesh.positions)
    pose = rest * np.array([1.4, 1.0, 1.0])
    assert np.array_equal(first.evaluate(pose).points, second.evaluate(pose).points)
    assert np.array_equal(first.evaluate(pose).points, first.evaluate(pose, deform="strain").points)
    # Isometric at rest: the geometric yarns, bit for bit.
    assert np.array_equal(first.evaluate(rest).points, first.evaluate(rest, deform="none").points)


def test_a_table_that_takes_minutes_is_said_so_before_it_is_made(tmp_path, monkeypatch):
    """strain_table_at_hand: a 2 x 2 rib chart's table is not quick (Blender refuses Strain-aware
    on it rather than not responding for minutes); a pattern argument of another type is named."""
    monkeypatch.setenv("KNIT_CACHE_DIR", str(tmp_path))
    rib = knit.strain_table_at_hand(knit.chart_pattern("k p k p\nk p k p\n", name="rib"))
    assert not rib["cached"] and not rib["quick"] and rib["seconds"] > 0, rib
    with pytest.raises(TypeError, match="pattern"):
        knit.strain_table_at_hand(3)


def test_mismatched_table_is_refused(table, tmp_path):
    path = str(tmp_path / "t.npy")
    table.save(path)
    import os
    shared = os.path.join(os.environ.get("KNIT_SHARED_DIR", ""), "patterns", "hylc", "stocktiny.pyp")
    if not os.path.exists(shared):
        pytest.skip("KNIT_SHARED_DIR patterns not present")
    with pytest.raises(knit.Error, match="t.npy"):
        knit.build_scene(shared, "plane", strain_table=path, build_plies=False)
