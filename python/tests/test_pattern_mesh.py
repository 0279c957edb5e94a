# Patterns and meshes: loading by name or file, meshes from numpy arrays, their errors.
import os
import warnings

import numpy as np
import pytest

import knit

SHARED = os.environ.get("KNIT_SHARED_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared"))


def quad(dtype=np.float64):
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=dtype)
    faces = np.array([[0, 1, 2], [0, 2, 3]])
    return positions, faces, positions[:, :2].copy()


def test_builtin_pattern_loads_by_name():
    p = knit.load_pattern("stockinette")
    assert "stockinette" in knit.builtin_patterns()
    assert p.px > 0 and p.radius > 0 and p.points.shape[1] == 3 and p.edge_count > 0


def test_pattern_file_loads():
    folder = os.path.join(SHARED, "patterns", "hylc")
    files = sorted(f for f in os.listdir(folder) if f.endswith(".pyp")) if os.path.isdir(folder) else []
    if not files:
        pytest.skip("no shared .pyp patterns in " + folder)
    assert knit.load_pattern(os.path.join(folder, files[0])).points.shape[0] > 0


def test_missing_pattern_file_raises_knit_error():
    with pytest.raises(knit.Error):
        knit.load_pattern("/nonexistent/pattern.pyp")


def test_builtin_mesh_resolution_sets_the_vertex_count():
    m = knit.load_mesh("plane", res_u=4, res_v=3)
    assert m.positions.shape == (20, 3) and m.faces.shape == (24, 3)
    assert set(knit.builtin_meshes()) >= {"plane", "drape"}


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_mesh_from_arrays_accepts_float32_and_float64(dtype):
    positions, faces, uvs = quad(dtype)
    m = knit.Mesh(positions, faces, uvs)
    np.testing.assert_array_equal(m.positions, positions.astype(np.float64))
    np.testing.assert_array_equal(m.face_uvs, m.faces)  # per-vertex UVs share the face indices


def test_mesh_from_arrays_with_separate_uv_indices():
    positions, faces, uvs = quad()
    m = knit.Mesh(positions, faces, uvs[::-1].copy(), faces[:, ::-1].copy())
    assert m.uvs.shape == (4, 2) and m.face_uvs[0].tolist() == [2, 1, 0]


def test_mesh_from_arrays_with_an_index_out_of_range_raises_knit_error():
    positions, faces, uvs = quad()
    with pytest.raises(knit.Error):
        knit.Mesh(positions, faces + 10, uvs)


def test_mesh_from_arrays_with_negative_index_names_the_row():
    positions, faces, uvs = quad()
    faces[1, 2] = -1
    with pytest.raises(knit.Error, match="faces: row 1"):
        knit.Mesh(positions, faces, uvs)


def test_mesh_from_integer_positions_is_refused():
    positions, faces, uvs = quad()
    with pytest.raises(knit.Error, match="float32 or float64"):
        knit.Mesh(positions.astype(np.int32), faces, uvs)


def test_scene_on_a_mesh_from_arrays():
    positions, faces, uvs = quad(np.float32)
    scene = knit.build_scene("stockinette", knit.Mesh(positions, faces, uvs), repeats=(3, 3), build_plies=False)
    assert scene.yarns.point_count > 0 and scene.plies.point_count == 0
    pts = scene.yarns.points
    assert pts[:, 0].min() > -0.1 and pts[:, 0].max() < 1.1


def test_vertex_normals_of_a_flat_quad_point_up():
    positions, faces, _ = quad()
    np.testing.assert_allclose(knit.vertex_normals(positions, faces), np.tile([0, 0, 1.0], (4, 1)))


FAIR_ISLE = "k k k k k k k k\nk k k k k k k k\n\nA A A A A A A A\nA B A A A A A A\nA=#ffffff B=#000000\nstranded\n"


def test_chart_text_relaxes_into_a_pattern(tmp_path, monkeypatch):
    monkeypatch.setenv("KNIT_CACHE_DIR", str(tmp_path))
    p = knit.chart_pattern("k yo k2tog k\nk k k k\n", name="lace")
    assert p.name == "lace"
    assert p.points.shape == (4 * 2 * 24, 3)
    assert p.radius == 0.001
    assert "chart:eyelet-mesh" in knit.builtin_charts()
    # A chart file goes through load_pattern, the same cell.
    f = tmp_path / "lace.chart"
    f.write_text("k yo k2tog k\nk k k k\n")
    assert knit.load_pattern(str(f)).points.shape == p.points.shape


def test_bad_chart_text_names_line_and_column():
    with pytest.raises(knit.Error, match=r"bad:1:8: row consumes 3 loops but the row below makes 4"):
        knit.chart_pattern("k yo k k\nk k k k\n", name="bad")
    with pytest.raises(knit.Error, match="yarn_radius must be positive"):
        knit.chart_pattern("k k\n", yarn_radius=0)


def test_chart_floats_flags_long_floats():
    floats = knit.chart_floats(FAIR_ISLE, name="band")
    long = [f for f in floats if f["too_long"]]
    assert len(long) == 1
    assert long[0]["row"] == 1 and long[0]["colour"] == "B" and long[0]["stitches"] == 7
    assert long[0]["columns"] == (3, 1) and long[0]["side"] == "back" and long[0]["line"] == 2
    assert not any(f["too_long"] for f in knit.chart_floats(FAIR_ISLE, max_float=7))


# Two one-stitch stripes per colour moving a column every row: after the 2 rows each A area sits on
# the other A area, so the repeat is knitted 4 rows tall (docs/charts.md, "Areas that wander").
WANDER = "k k k k\nk k k k\n\nB A B A\nA B A B\nA=#ffffff B=#000000\nintarsia\n"


def test_chart_warnings_say_what_knit_chart_says():
    stacked = knit.chart_warnings(WANDER, name="w.chart")
    assert stacked == ["w.chart: intarsia: the colour areas move round the period and, after the chart's 2 rows, "
                       "arrive on other areas of their colour; each area's yarn comes back to itself after 4 rows, "
                       "so the chart's repeat is knitted 4 rows tall (its rows 2 times over)"]
    floats = knit.chart_warnings(FAIR_ISLE, name="band")
    assert floats == ["band:2: row 1: the float of colour B over columns 3-1 (round the repeat) is 7 stitches "
                      "long, longer than the float limit (max_float) of 5 stitches (long floats snag: catch it "
                      "or shorten the run)"]
    assert knit.chart_warnings(FAIR_ISLE, max_float=7) == []
    assert knit.chart_warnings("k k\nk k\n") == []
    with pytest.raises(knit.Error, match="max_float must be at least 1"):
        knit.chart_warnings(FAIR_ISLE, max_float=0)


def test_a_stacked_chart_warns_before_it_relaxes(tmp_path, monkeypatch):
    # As errors, the warning stops chart_pattern and load_pattern before the (40 s) relaxation.
    monkeypatch.setenv("KNIT_CACHE_DIR", str(tmp_path))
    f = tmp_path / "w.chart"
    f.write_text(WANDER)
    with warnings.catch_warnings():
        warnings.simplefilter("error", knit.ChartWarning)
        with pytest.raises(knit.ChartWarning, match=r"w: intarsia: .* knitted 4 rows tall \(its rows 2 times over\)"):
            knit.chart_pattern(WANDER, name="w")
        with pytest.raises(knit.ChartWarning, match=r"w.chart: intarsia: .* knitted 4 rows tall"):
            knit.load_pattern(str(f))
    assert issubclass(knit.ChartWarning, UserWarning)
    assert list(tmp_path.iterdir()) == [f]  # nothing relaxed, nothing cached


def test_build_scene_given_a_chart_by_name_warns_as_load_pattern(tmp_path, monkeypatch):
    # A chart file or chart:NAME passed straight to build_scene warns before the relaxation, in
    # load_pattern's words, pointing at the caller's line.
    monkeypatch.setenv("KNIT_CACHE_DIR", str(tmp_path))
    f = tmp_path / "w.chart"
    f.write_text(WANDER)
    band = tmp_path / "band.chart"
    band.write_text(FAIR_ISLE)
    with warnings.catch_warnings():
        warnings.simplefilter("error", knit.ChartWarning)
        with pytest.raises(knit.ChartWarning) as raised:
            knit.build_scene(str(f), "plane")
        with pytest.raises(knit.ChartWarning, match=r"band.chart:2: row 1: the float of colour B over columns 3-1"):
            knit.build_scene(pattern=str(band), mesh="plane")
        with pytest.raises(knit.ChartWarning, match=r"longer than the float limit \(max_float\) of 2 stitches"):
            knit.build_scene(str(band), "plane", max_float=2)
    assert str(raised.value) == knit.chart_warnings(WANDER, name=str(f))[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["band.chart", "w.chart"]  # nothing relaxed
    with pytest.warns(knit.ChartWarning) as shown:
        with pytest.raises(TypeError):  # warned first, then refused by the pipeline: nothing relaxed
            knit.build_scene(str(band), "plane", no_such_keyword=1)
    assert len(shown) == 1 and shown[0].filename == __file__


def test_a_long_float_warns_and_the_pattern_still_relaxes(tmp_path, monkeypatch):
    monkeypatch.setenv("KNIT_CACHE_DIR", str(tmp_path))
    band = "k k k k k k k\n\nA B A A A A A\nA=#ffffff B=#000000\nstranded\n"
    with pytest.warns(knit.ChartWarning, match=r"band:1: row 1: the float of colour B over columns 3-1") as caught:
        p = knit.chart_pattern(band, name="band")
    assert len(caught) == 1 and caught[0].filename == __file__  # pointed at the caller's line
    assert p.points.shape[0] > 0
    with warnings.catch_warnings():
        warnings.simplefilter("error", knit.ChartWarning)
        knit.chart_pattern(band, name="band", max_float=6)  # within the limit: silent
        knit.load_pattern("chart:eyelet-mesh")  # a built-in without floats or stacking: silent
