# build_scene, the scene's views, evaluate on new poses, plies.
import numpy as np
import pytest

import knit


@pytest.fixture(scope="module")
def scene():
    return knit.build_scene("stockinette", "drape", repeats=(8, 8), plies=2)


def test_build_scene_counts_match_the_stats(scene):
    stats = scene.stats
    assert scene.yarns.point_count == stats["yarn_vertices"] > 0
    assert scene.plies.point_count == stats["ply_vertices"] > 0
    assert scene.yarns.curve_count == stats["yarns"]
    assert scene.repeats == (8.0, 8.0)


def test_views_are_read_only_float64_without_copy(scene):
    a = scene.yarns.points
    assert a.dtype == np.float64 and a.shape == (scene.yarns.point_count, 3)
    assert not a.flags.writeable
    with pytest.raises(ValueError):
        a[0, 0] = 1.0
    assert np.shares_memory(a, scene.yarns.points)  # the same buffer, every time


def test_view_keeps_its_owner_alive():
    points = knit.build_scene("stockinette", "plane", repeats=(2, 2)).yarns.points
    import gc
    gc.collect()
    assert np.isfinite(points).all() and points.shape[0] > 0


def test_offsets_partition_the_points(scene):
    off = scene.yarns.offsets
    assert off[0] == 0 and off[-1] == scene.yarns.point_count
    assert len(off) == scene.yarns.curve_count + 1 and (np.diff(off) >= 0).all()


def test_evaluate_at_rest_reproduces_the_scene_yarns(scene):
    yarns = scene.evaluate(scene.mesh.positions)
    np.testing.assert_array_equal(yarns.points, scene.yarns.points)
    np.testing.assert_array_equal(yarns.normals, scene.yarns.normals)


def test_evaluate_accepts_float32_and_follows_a_translation(scene):
    moved = (scene.mesh.positions + [0.0, 0.0, 1.0]).astype(np.float32)
    yarns = scene.evaluate(moved)
    # float32 input rounds the positions (~1e-7 relative); the yarns move by the same offset.
    np.testing.assert_allclose(yarns.points - scene.yarns.points, np.tile([0, 0, 1.0], (yarns.point_count, 1)),
                               atol=1e-6)


def test_evaluate_with_a_wrong_vertex_count_raises_knit_error(scene):
    with pytest.raises(knit.Error, match="positions: expected"):
        scene.evaluate(np.zeros((3, 3)))


def test_evaluate_with_a_wrong_shape_raises_knit_error(scene):
    with pytest.raises(knit.Error, match=r"shape \(n, 3\)"):
        scene.evaluate(np.zeros(12))


def test_evaluate_plies_at_rest_matches_the_scene_plies(scene):
    # The Animator's rest pose equals make_plies to rounding (its twist phase and first frame are
    # computed at bind time, by other operations), not bit for bit.
    plies = scene.evaluate_plies(scene.mesh.positions)
    np.testing.assert_allclose(plies.points, scene.plies.points, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(plies.offsets, scene.plies.offsets)


def test_make_plies_on_evaluated_yarns_matches_the_scene_plies(scene):
    plies = knit.make_plies(scene.yarns, scene.yarn_radius, count=2)
    np.testing.assert_array_equal(plies.points, scene.plies.points)
    assert plies.ply_radius == pytest.approx(scene.ply_radius)
    assert set(np.unique(plies.ply_of_curve)) == {0, 1}


def test_twist_other_than_s_or_z_raises_naming_the_argument():
    with pytest.raises(knit.Error, match="twist: expected 'S' or 'Z'"):
        knit.build_scene(twist="X")


def test_unknown_pattern_raises_knit_error_with_the_library_message():
    with pytest.raises(knit.Error, match="unknown pattern 'nope'"):
        knit.build_scene("nope")
    assert issubclass(knit.Error, Exception)


def test_binding_has_one_entry_per_yarn_vertex(scene):
    b = scene.binding
    assert b.vertex_count == scene.yarns.point_count
    assert b.bary.shape == (b.vertex_count, 2) and b.face.shape == (b.vertex_count,)
    assert b.face.max() < len(scene.mesh.faces)


def test_evaluate_plies_keeps_the_rest_layout_when_the_yarns_stretch(scene):
    stretched = scene.mesh.positions * [1.5, 1.0, 1.0]
    free = knit.make_plies(scene.evaluate(stretched), scene.yarn_radius, count=2)  # resampled afresh
    kept = scene.evaluate_plies(stretched)
    assert free.point_count != scene.plies.point_count  # resampling follows the yarn length
    np.testing.assert_array_equal(kept.offsets, scene.plies.offsets)
    # Same curves: the kept layout spans the stretched yarns (x range grows by ~1.5).
    assert np.ptp(kept.points[:, 0]) == pytest.approx(np.ptp(free.points[:, 0]), rel=1e-3)


def test_max_memory_refuses_a_scene_over_the_budget_before_building_it():
    with pytest.raises(knit.Error, match=r"over the memory budget \(max_memory\) of"):
        knit.build_scene("stockinette", "drape", repeats=(64, 64), max_memory="1M")
    assert knit.build_scene("stockinette", "plane", repeats=(2, 2), max_memory="1G").yarns.point_count > 0


def test_max_memory_that_is_not_a_size_is_refused_naming_the_keyword():
    with pytest.raises(knit.Error, match=r"the memory budget \(max_memory\) 'lots': expected a size") as e:
        knit.build_scene("stockinette", "plane", repeats=(2, 2), max_memory="lots")
    assert "--" not in str(e.value)


@pytest.mark.parametrize("keywords, keyword", [
    (dict(samples_per_turn=1), "samples_per_turn"),
    (dict(ply_pitch=-1.0), "ply_pitch"),
    (dict(plies=20), "plies"),
    (dict(repeats=(64, 64), max_memory="1M"), "max_memory"),
])
def test_library_messages_name_the_python_keyword_not_the_cli_flag(keywords, keyword):
    with pytest.raises(knit.Error, match=keyword) as e:
        knit.build_scene("stockinette", "drape", **keywords)
    assert "--" not in str(e.value)
