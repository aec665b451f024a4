"""Colours and other attributes, outliers and trimming through the Python module (issue 16)."""

import numpy as np
import pytest

import pdd
from conftest import EDGE, fibonacci_sphere


def ramp(points):
    """An analytic colour field: red follows the height, green and blue fixed."""
    red = np.round(127.5 * (points[:, 2] + 1)).astype(np.uint8)
    return np.column_stack([red, np.full_like(red, 40), np.full_like(red, 200)])


def test_a_colour_ramp_comes_out_as_a_colour_ramp(sphere):
    points, normals = sphere
    mesh = pdd.reconstruct(points, normals, ramp(points), target_edge=EDGE, threads=2)
    assert mesh.colors is not None and mesh.colors.shape == (len(mesh.vertices), 3)
    assert mesh.colors.dtype == np.uint8
    error = np.abs(mesh.colors[:, 0].astype(float) - 127.5 * (mesh.vertices[:, 2] + 1))
    assert error.mean() < 3
    assert np.all(mesh.colors[:, 1] == 40) and np.all(mesh.colors[:, 2] == 200)
    assert mesh.stats["attributes"] == ["red", "green", "blue"]
    # Float colours stay floats (0-1); attributes="none" drops them.
    floats = pdd.reconstruct(points, normals, ramp(points) / 255.0, target_edge=EDGE, threads=2)
    assert floats.colors.dtype == np.float64 and floats.colors.max() <= 1
    bare = pdd.reconstruct(points, normals, ramp(points), attributes="none", target_edge=EDGE,
                           threads=2)
    assert bare.colors is None


def test_bad_colours_raise_value_error(sphere):
    points, normals = sphere
    with pytest.raises(ValueError, match=r"colors: expected an array of shape \(n, 3\) or \(n, 4\)"):
        pdd.reconstruct(points, normals, np.zeros((len(points), 2), np.uint8))
    with pytest.raises(ValueError, match="colors: expected uint8"):
        pdd.reconstruct(points, normals, np.zeros((len(points), 3), np.int64))
    wrong = np.full((len(points), 3), 0.5)
    wrong[7, 1] = 1.5
    with pytest.raises(ValueError, match=r"point 8: the colour property 'green' is 1.5, outside 0-1"):
        pdd.reconstruct(points, normals, wrong)
    with pytest.raises(ValueError, match="--attributes: the points have no property 'intensity'"):
        pdd.reconstruct(points, normals, attributes="intensity")


def test_ply_round_trips_keep_colours_and_attributes(tmp_path, sphere_mesh):
    n = len(sphere_mesh.vertices)
    mesh = pdd.Mesh(sphere_mesh.vertices, sphere_mesh.faces, colors=ramp(sphere_mesh.vertices),
                    attributes={"confidence": np.linspace(0, 1, n).astype(np.float32),
                                "segment_index": np.arange(n, dtype=np.int32) % 5})
    pdd.write_mesh(tmp_path / "c.ply", mesh)
    back = pdd.read_mesh(tmp_path / "c.ply")
    assert np.array_equal(back.colors, mesh.colors) and back.colors.dtype == np.uint8
    assert np.array_equal(back.attributes["confidence"], mesh.attributes["confidence"])
    assert back.attributes["segment_index"].dtype == np.int32
    assert np.array_equal(back.attributes["segment_index"], mesh.attributes["segment_index"])
    points, normals = fibonacci_sphere(100)
    pdd.write_mesh(tmp_path / "c.off", mesh)
    assert (tmp_path / "c.off").read_text().startswith("COFF")


def test_find_outliers_and_the_run_drop_the_same_strays(sphere):
    points, normals = sphere
    rng = np.random.default_rng(0)
    strays = rng.uniform(-1.1, 1.1, (40, 3))
    strays = strays[np.abs(np.linalg.norm(strays, axis=1) - 1) > 0.7]
    stray_normals = rng.normal(size=strays.shape)
    stray_normals /= np.linalg.norm(stray_normals, axis=1)[:, None]
    all_points = np.vstack([points, strays])
    all_normals = np.vstack([normals, stray_normals])
    mask = pdd.find_outliers(all_points)
    assert mask.dtype == np.bool_ and mask.shape == (len(all_points),)
    assert not mask[: len(points)].any()
    assert mask[len(points):].sum() >= len(strays) // 2
    with pytest.warns(UserWarning, match=f"dropped {mask.sum()} outlier"):
        mesh = pdd.reconstruct(all_points, all_normals, target_edge=0.1, threads=2)
    assert mesh.stats["outliers"]["removed"] == mask.sum()
    assert not pdd.find_outliers(all_points, ratio=0).any()


def test_trim_opens_a_hemisphere(sphere):
    points, normals = sphere
    upper = points[:, 2] > 0
    mesh = pdd.reconstruct(points[upper], normals[upper], trim=2, target_edge=0.08, threads=2)
    surface = pdd.quality(mesh)["surface"]
    assert not surface["closed"] and surface["manifold"] and surface["components"] == 1
    assert mesh.stats["trim"]["trimmed"] and mesh.stats["trim"]["boundary_loops"] == 1
    assert mesh.vertices[:, 2].min() > -0.3


def test_open3d_conversions_carry_colours(sphere):
    o3d = pytest.importorskip("open3d")
    points, normals = sphere
    cloud = pdd.PointCloud(points, normals, ramp(points)).to_open3d()
    assert cloud.has_colors()
    back = pdd.PointCloud.from_open3d(cloud)
    assert np.allclose(back.colors, ramp(points) / 255.0)
    mesh = pdd.reconstruct(cloud, target_edge=EDGE, threads=2)
    assert mesh.colors is not None and mesh.colors.dtype == np.float64
    assert mesh.to_open3d().has_vertex_colors()
    assert isinstance(mesh.to_open3d(), o3d.geometry.TriangleMesh)
