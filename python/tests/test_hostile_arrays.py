# Every array argument of the module is checked as knit.Mesh checks its arrays (shape, dtype,
# finite values within the float32 range of mesh files, index counts), in every function that
# takes one, and refused with knit.Error naming the argument (and the row), never a crash, a
# non-finite result or another front end's spelling.
import numpy as np
import pytest

import knit


@pytest.fixture(scope="module")
def scene():
    return knit.build_scene("stockinette", "plane", repeats=(3, 3), res_u=6, res_v=6, build_plies=False)


def arrays(scene):
    m = scene.mesh
    return dict(positions=np.array(m.positions), faces=np.array(m.faces), uvs=np.array(m.uvs),
                face_uvs=np.array(m.face_uvs))


# (name, call taking the arrays as keywords, the float arguments it takes)
CALLS = [
    ("Mesh", lambda s, a: knit.Mesh(**a), ["positions", "uvs"]),
    ("vertex_normals", lambda s, a: knit.vertex_normals(a["positions"], a["faces"]), ["positions"]),
    ("Scene.evaluate", lambda s, a: s.evaluate(a["positions"]), ["positions"]),
    ("Scene.evaluate_plies", lambda s, a: s.evaluate_plies(a["positions"]), ["positions"]),
    ("_evaluate_seconds_in_cpp", lambda s, a: knit._knit._evaluate_seconds_in_cpp(s, a["positions"]), ["positions"]),
]
FLOAT_CASES = [(name, call, arg) for name, call, args in CALLS for arg in args]


@pytest.mark.parametrize("value, words", [(np.nan, "is not finite"), (np.inf, "is not finite"),
                                          (-np.inf, "is not finite"), (1e39, "beyond the float32 range")])
@pytest.mark.parametrize("name, call, arg", FLOAT_CASES, ids=[f"{n}-{a}" for n, _, a in FLOAT_CASES])
def test_values_that_are_not_finite_or_beyond_float32_are_refused_naming_argument_and_row(scene, name, call, arg,
                                                                                           value, words):
    a = arrays(scene)
    bad = a[arg].copy()
    bad[3, 1] = value
    a[arg] = bad
    with pytest.raises(knit.Error, match=rf"^{arg}: row 3 \(.*\) .*{words}") as e:
        call(scene, a)
    assert "--" not in str(e.value)


@pytest.mark.parametrize("name, call, arg", FLOAT_CASES, ids=[f"{n}-{a}" for n, _, a in FLOAT_CASES])
@pytest.mark.parametrize("change, words", [
    (lambda x: x.ravel(), r"expected an array of shape \(n, \d\), got \(\d+,\)"),
    (lambda x: x[None], r"expected an array of shape \(n, \d\), got \(1, \d+, \d\)"),
    (lambda x: x.astype(np.float16), "expected float32 or float64 values, got dtype float16"),
    (lambda x: x.astype(complex), "expected float32 or float64 values, got dtype complex128"),
    (lambda x: x.astype(np.int64), "expected float32 or float64 values, got dtype int64"),
])
def test_wrong_shapes_and_dtypes_are_refused_naming_the_argument(scene, name, call, arg, change, words):
    a = arrays(scene)
    a[arg] = change(a[arg])
    with pytest.raises(knit.Error, match=rf"^{arg}: {words}"):
        call(scene, a)


@pytest.mark.parametrize("name, call", [(n, c) for n, c, _ in CALLS[:2]], ids=[n for n, _, _ in CALLS[:2]])
def test_face_indices_beyond_the_positions_are_refused_not_read(scene, name, call):
    # vertex_normals read past the positions array with these (a segmentation fault).
    a = arrays(scene)
    for index in (len(a["positions"]), 10**6, 2**32 - 1):
        faces = a["faces"].copy()
        faces[2, 1] = index
        a["faces"] = faces
        with pytest.raises(knit.Error, match=rf"face.* 2 .*{index}"):
            call(scene, a)


def test_index_dtypes_and_ranges_are_checked_with_the_row(scene):
    a = arrays(scene)
    for faces, words in [(a["faces"].astype(float), "expected integer indices, got dtype float64"),
                         (a["faces"].astype(bool), "expected integer indices, got dtype bool"),
                         (a["faces"].astype(np.uint64) + np.uint64(2**63), r"row 0 has the index 9223372036854775808"),
                         (a["faces"].astype(np.int64) - 2**33, r"row 0 has the index -"),
                         (a["faces"][:, :2], r"expected an array of shape \(n, 3\)")]:
        with pytest.raises(knit.Error, match=rf"^faces: {words}"):
            knit.vertex_normals(a["positions"], faces)
        with pytest.raises(knit.Error, match=rf"^faces: {words}"):
            knit.Mesh(a["positions"], faces, a["uvs"], a["face_uvs"])


def test_wrong_row_counts_name_the_expected_count(scene):
    a = arrays(scene)
    with pytest.raises(knit.Error, match=rf"positions: expected {len(a['positions'])} rows .* got 3"):
        scene.evaluate_plies(a["positions"][:3])


@pytest.mark.parametrize("scale", [1e-30, 1.0, 1e30])
def test_finite_poses_give_finite_results_at_any_scale_in_float32(scene, scale):
    a = arrays(scene)
    # The rest pose scaled about its centre; a collapsed pose (every vertex at one point) too.
    for pose in (a["positions"] * scale, np.zeros_like(a["positions"])):
        for result in (scene.evaluate(pose), scene.evaluate_plies(pose)):
            assert np.isfinite(result.points).all()


def test_repeats_that_are_not_a_pair_of_numbers_raise_type_error_naming_repeats():
    for repeats in ("ab", (1, 2, 3), ("a", 2)):
        with pytest.raises(TypeError, match=r"^repeats: expected None or a pair \(U, V\) of numbers"):
            knit.build_scene("stockinette", "plane", repeats=repeats)


def test_mesh_resolution_is_named_by_its_keywords():
    with pytest.raises(knit.Error, match=r"the mesh resolution \(res_u, res_v\) -5 x 32 quads is too small") as e:
        knit.build_scene("stockinette", "plane", repeats=(2, 2), res_u=-5)
    assert "resU" not in str(e.value)
    # A resolution the module allows (up to 1e8 quads) but the budget does not: refused before
    # the mesh is made, naming the quads and the keywords.
    with pytest.raises(knit.Error, match=r"needs about .* for 1e\+08 quads of the built-in mesh 'plane'.*"
                                         r"lower the mesh resolution \(res_u, res_v\)"):
        knit.build_scene("stockinette", "plane", repeats=(2, 2), res_u=10000, res_v=10000, max_memory="1G")


def test_a_tiny_ply_pitch_is_estimated_before_the_first_evaluate_plies():
    # A scene bound without plies (as the Blender add-on binds) was never estimated for them: the
    # first evaluate_plies resampled every yarn at this pitch and took all memory.
    scene = knit.build_scene("stockinette", "plane", repeats=(6, 6), ply_pitch=1e-12, build_plies=False)
    with pytest.raises(knit.Error, match=r"needs about .* ply vertices, over the memory budget .*"
                                         r"raise the ply pitch \(ply_pitch\)") as e:
        scene.evaluate_plies(scene.mesh.positions)
    assert "--" not in str(e.value)
    np.testing.assert_array_equal(scene.evaluate(scene.mesh.positions).points, scene.yarns.points)  # yarns need no plies


def test_error_words_let_another_front_end_name_the_settings():
    with pytest.raises(knit.Error) as e:
        knit.build_scene("stockinette", "plane", repeats=(64, 64), max_memory="1M")
    assert "lower the repeats (repeats)" in str(e.value)
    assert "(repeats)" not in e.value.words and "lower the repeats or raise the memory budget" in e.value.words
    spelled = knit.spell_settings(e.value.words, [("the repeats", "Repeats")])
    assert "lower the repeats (Repeats) or raise the memory budget" in spelled and "max_memory" not in spelled
