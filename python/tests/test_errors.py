"""Bad input and options raise ValueError with the command line's messages."""

import subprocess

import numpy as np
import pytest

import pdd


@pytest.mark.parametrize("points, message", [
    (np.zeros((10, 2)), r"points: expected an array of shape \(n, 3\), got shape \(10, 2\)"),
    (np.zeros(9), r"points: expected an array of shape \(n, 3\), got shape \(9,\)"),
    (np.array([["a", "b", "c"]]), "points: expected real numbers"),
    (object(), "points: expected a numpy array"),
])
def test_wrong_shapes_and_types(sphere, points, message):
    with pytest.raises(ValueError, match=message):
        pdd.reconstruct(points, sphere[1])


def test_nans_are_named_with_their_point(sphere):
    points = sphere[0].copy()
    points[6, 1] = np.nan
    with pytest.raises(ValueError, match=r"^points: .*7"):
        pdd.reconstruct(points, sphere[1])


def test_normals_must_match_the_points(sphere):
    with pytest.raises(ValueError, match="normals: 1999 normals for 2000 points"):
        pdd.reconstruct(sphere[0], sphere[1][1:])
    with pytest.raises(ValueError, match="points: 10 points are too few to estimate normals"):
        pdd.reconstruct(sphere[0][::200])


@pytest.mark.parametrize("options, message", [
    ({"target_edge": -1.0}, r"--target-edge: must be a number > 0, got '-1.0'"),
    ({"iterations": 0}, r"--iterations: must be an integer from 1 to 1000, got '0'"),
    ({"solver": "octree"}, r"--solver: must be one of ssd, poisson, spectral, got 'octree'"),
    ({"seed": -1}, r"--seed: must be an integer from 0 to 18446744073709551615, got '-1'"),
    ({"seed": 2**64}, r"--seed: must be an integer from 0 to 18446744073709551615"),
    ({"max_memory": "lots"}, r"--max-memory: 'lots' is not a memory size"),
    ({"iterations": 2.5}, r"--iterations: must be an integer, got 2.5"),
    ({"no_cleanup": 1}, r"--no-cleanup: must be True or False, got 1"),
    ({"target_edge": float("nan")}, r"--target-edge: must be a number > 0, got 'nan'"),
    ({"enlarge_ratio": 1e300}, r"--enlarge-ratio: must be a number > 1 and <= 100, got '1e\+300'"),
    ({"radius_edge": 0.3}, r"--radius-edge: must be a number >= 1, got '0.3'"),
    ({"threads": 100000}, r"--threads: must be an integer from 0 to \d+, got '100000'"),
    ({"sphere_points": 4}, r"initial domain: the hull of 4 points on the domain sphere "
                           r"\(--sphere-points\) reaches 0.227 of its radius.*"
                           r"use more points or a ratio above 4.41"),
    ({"max_memory": "\x1b[2J" + "9" * 1000}, r"--max-memory: '\\x1b\[2J9{36}\.\.\.' is not"),
])
def test_bad_options_name_the_option_and_the_bound(sphere, options, message):
    with pytest.raises(ValueError, match=message):
        pdd.reconstruct(*sphere, **options)


def test_the_command_line_gives_the_same_messages(pdd_binary, tmp_path):
    run = subprocess.run([pdd_binary, "reconstruct", "in.ply", "-o", str(tmp_path / "o.ply"),
                          "--iterations", "0"], capture_output=True, text=True)
    assert run.returncode == 2
    assert run.stderr == "pdd: error: --iterations: must be an integer from 1 to 1000, got '0'\n"


def test_unknown_keyword_is_a_type_error(sphere):
    with pytest.raises(TypeError, match="unexpected keyword argument 'target_edges'"):
        pdd.reconstruct(*sphere, target_edges=0.1)


def test_bad_meshes(tmp_path):
    vertices = np.eye(3)
    with pytest.raises(ValueError, match="mesh: face 1 refers to vertex 3, but the mesh has 3"):
        pdd.quality(pdd.Mesh(vertices, [[0, 1, 3]]))
    with pytest.raises(ValueError, match="mesh.faces: expected integers"):
        pdd.quality(pdd.Mesh(vertices, [[0.0, 1.0, 2.0]]))
    with pytest.raises(ValueError, match="mesh: the mesh has no faces"):
        pdd.write_mesh(tmp_path / "m.ply", pdd.Mesh(vertices, np.zeros((0, 3), int)))
    with pytest.raises(ValueError, match="a: the mesh has no area"):
        pdd.compare(pdd.Mesh(np.zeros((3, 3)), [[0, 1, 2]]), pdd.Mesh(vertices, [[0, 1, 2]]))
    with pytest.raises(ValueError, match="samples: must be an integer from 1 to 100000000"):
        pdd.compare(pdd.Mesh(vertices, [[0, 1, 2]]), pdd.Mesh(vertices, [[0, 1, 2]]),
                    samples=2**40)
    with pytest.raises(ValueError, match=r"mesh: the vertices span 1.73e\+200"):
        pdd.quality(pdd.Mesh(vertices * 1e200, [[0, 1, 2]]))
    with pytest.raises(ValueError, match=r"a: the vertices span 1e\+308"):
        far = vertices.copy()
        far[2] = [0, 0, -1e308]
        pdd.compare(pdd.Mesh(far, [[0, 1, 2]]), pdd.Mesh(vertices, [[0, 1, 2]]))
    assert not (tmp_path / "m.ply").exists()


def test_bad_files_raise_value_error_naming_them(tmp_path):
    with pytest.raises(ValueError, match="absent.ply: no such file"):
        pdd.read_points(tmp_path / "absent.ply")
    bad = tmp_path / "bad.xyz"
    bad.write_text("1 2 3\n4 5\n")
    with pytest.raises(ValueError, match="bad.xyz"):
        pdd.read_points(bad)
    with pytest.raises(ValueError, match="no such file"):
        pdd.read_mesh(tmp_path / "absent.off")
