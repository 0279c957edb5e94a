# One animation path: Scene.evaluate / evaluate_plies are knit animate's Animator. Frame k of the
# module equals frame k of `knit animate`'s point cache, bit for bit after the cache's float32
# rounding; evaluations from several threads at once equal the sequential ones bit for bit.
import os
import shutil
import struct
import subprocess
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import knit

REPEATS = (4, 4)


def knit_cli():
    """The knit command line: KNIT_CLI (set by ctest), else <build>/apps/knit/knit, else PATH."""
    build = os.environ.get("KNIT_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
    for candidate in (os.environ.get("KNIT_CLI"), os.path.join(build, "apps", "knit", "knit"), shutil.which("knit")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return None


def write_obj(path, positions, faces, uvs, face_uvs):
    """An OBJ whose coordinates read back exactly: float32 values, written with Python's
    round-trip repr, so any reader (float or double) gets the same numbers."""
    lines = ["v %r %r %r" % tuple(float(c) for c in p) for p in positions]
    lines += ["vt %r %r" % tuple(float(c) for c in t) for t in uvs]
    lines += ["f %d/%d %d/%d %d/%d" % (f[0] + 1, t[0] + 1, f[1] + 1, t[1] + 1, f[2] + 1, t[2] + 1)
              for f, t in zip(faces, face_uvs)]
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


def read_pc2(path):
    """(frames, points, 3) float32 of a PC2 point cache."""
    with open(path, "rb") as f:
        magic, version, points, start, rate, frames = struct.unpack("<12siiffi", f.read(32))
        assert magic == b"POINTCACHE2\0" and version == 1
        data = np.frombuffer(f.read(), dtype="<f4")
    assert data.size == frames * points * 3
    return data.reshape(frames, points, 3)


def poses(rest):
    """Frame 1 the rest pose, then a stretch, a bend with a turn and a travelling wave."""
    x, y, z = rest[:, 0], rest[:, 1], rest[:, 2]
    c, s = np.cos(0.7), np.sin(0.7)
    bent = np.stack([c * x - s * (z + 0.2 * y * y), s * x + c * (z + 0.2 * y * y), y], axis=1) + [0.1, -0.05, 0.3]
    wave = rest + np.stack([0 * x, 0 * y, 0.03 * np.sin(12.0 * x + 5.0 * y)], axis=1)
    return [rest, rest * [1.3, 0.9, 1.0], bent, wave]


@pytest.fixture(scope="module")
def sequence(tmp_path_factory):
    """Four OBJ frames of the built-in drape (float32 coordinates) in a temporary folder."""
    folder = tmp_path_factory.mktemp("frames")
    mesh = knit.load_mesh("drape", res_u=12, res_v=12)
    rest = np.asarray(mesh.positions, dtype=np.float32).astype(np.float64)
    uvs = np.asarray(mesh.uvs, dtype=np.float32).astype(np.float64)
    paths = []
    for k, p in enumerate(poses(rest), start=1):
        path = str(folder / ("frame_%04d.obj" % k))
        write_obj(path, np.asarray(p, dtype=np.float32), mesh.faces, uvs, mesh.face_uvs)
        paths.append(path)
    return folder, paths


def animate(sequence, tmp_path, *extra):
    cli = knit_cli()
    if cli is None:
        pytest.skip("the knit command line is not built (cmake --build build --target knit_cli)")
    folder, paths = sequence
    out = str(tmp_path / "cache.pc2")
    subprocess.run([cli, "animate", "-q", "--no-stats", "--frames", str(folder / "frame_%04d.obj"),
                    "--repeats", str(REPEATS[0]), str(REPEATS[1]), "--plies", "3", "--twist", "Z",
                    *extra, "-o", out], check=True, capture_output=True)
    return read_pc2(out)


def test_evaluate_plies_frame_k_is_knit_animate_frame_k(sequence, tmp_path):
    folder, paths = sequence
    cache = animate(sequence, tmp_path)
    scene = knit.build_scene("stockinette", paths[0], repeats=REPEATS, plies=3, twist="Z")
    assert cache.shape[0] == len(paths)
    for k, path in enumerate(paths):
        plies = scene.evaluate_plies(knit.load_mesh(path).positions)
        assert plies.point_count == cache.shape[1]
        # Bit for bit after the cache's rounding to float32: the same Animator on the same numbers.
        np.testing.assert_array_equal(plies.points.astype(np.float32), cache[k], err_msg=f"frame {k + 1}")


def test_evaluate_frame_k_is_knit_animate_yarn_frame_k(sequence, tmp_path):
    folder, paths = sequence
    cache = animate(sequence, tmp_path, "--export", "yarns")
    scene = knit.build_scene("stockinette", paths[0], repeats=REPEATS, plies=3, twist="Z", build_plies=False)
    for k, path in enumerate(paths):
        yarns = scene.evaluate(knit.load_mesh(path).positions)
        np.testing.assert_array_equal(yarns.points.astype(np.float32), cache[k], err_msg=f"frame {k + 1}")


@pytest.fixture(scope="module")
def scene():
    return knit.build_scene("stockinette", "drape", repeats=(6, 6), plies=2)


def test_evaluate_plies_keeps_the_point_layout_on_every_pose(scene):
    rest = scene.mesh.positions
    for pose in poses(rest):
        plies = scene.evaluate_plies(pose)
        np.testing.assert_array_equal(plies.offsets, scene.plies.offsets)
        np.testing.assert_array_equal(plies.yarn_of_curve, scene.plies.yarn_of_curve)


def test_evaluate_plies_on_a_rigid_motion_moves_the_plies_by_that_motion(scene):
    rest = scene.mesh.positions
    c, s = np.cos(2.0), np.sin(2.0)
    r = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    t = np.array([0.3, -1.0, 2.0])
    before = np.array(scene.evaluate_plies(rest).points)
    after = scene.evaluate_plies(rest @ r.T + t).points
    np.testing.assert_allclose(after, before @ r.T + t, rtol=0, atol=1e-12)


def test_evaluate_plies_needs_no_plies_built_with_the_scene():
    built = knit.build_scene("stockinette", "plane", repeats=(2, 2))
    bare = knit.build_scene("stockinette", "plane", repeats=(2, 2), build_plies=False)
    assert bare.plies.point_count == 0
    pose = bare.mesh.positions * [1.0, 1.2, 1.0]
    np.testing.assert_array_equal(bare.evaluate_plies(pose).points, built.evaluate_plies(pose).points)


def test_concurrent_evaluations_equal_the_sequential_ones_bit_for_bit():
    # A fresh scene, so the first evaluations also race to make the scene's animators.
    scene = knit.build_scene("stockinette", "drape", repeats=(6, 6), plies=2)
    rest = scene.mesh.positions
    pose_list = [p * (1.0 + 0.05 * i) for i in range(3) for p in poses(rest)]  # 12 different poses

    def plies(p):
        return np.array(scene.evaluate_plies(p).points)

    def yarns(p):
        return np.array(scene.evaluate(p).points)

    with ThreadPoolExecutor(max_workers=4) as pool:
        parallel_plies = list(pool.map(plies, pose_list))
        parallel_yarns = list(pool.map(yarns, pose_list))
        mixed = list(pool.map(lambda i: (plies if i % 2 else yarns)(pose_list[i]), range(len(pose_list))))
    for i, p in enumerate(pose_list):
        sequential_plies, sequential_yarns = plies(p), yarns(p)
        assert parallel_plies[i].tobytes() == sequential_plies.tobytes(), f"pose {i}: plies differ"
        assert parallel_yarns[i].tobytes() == sequential_yarns.tobytes(), f"pose {i}: yarns differ"
        assert mixed[i].tobytes() == (sequential_plies if i % 2 else sequential_yarns).tobytes(), f"pose {i}"


def test_evaluate_plies_errors_name_no_command_line_flag(scene):
    with pytest.raises(knit.Error) as e:
        scene.evaluate_plies(np.full((len(scene.mesh.positions), 3), np.nan))
    assert "--" not in str(e.value)
    with pytest.raises(knit.Error, match="positions: expected") as e:
        scene.evaluate_plies(np.zeros((3, 3)))
    assert "--" not in str(e.value)


def test_evaluate_needs_no_valid_ply_options():
    # The yarns alone do not depend on the ply options: a scene built without plies evaluates its
    # yarns whatever they are; only evaluate_plies checks them.
    scene = knit.build_scene("stockinette", "plane", repeats=(2, 2), samples_per_turn=1, build_plies=False)
    yarns = scene.evaluate(scene.mesh.positions)
    np.testing.assert_array_equal(yarns.points, scene.yarns.points)
    with pytest.raises(knit.Error):
        scene.evaluate_plies(scene.mesh.positions)
