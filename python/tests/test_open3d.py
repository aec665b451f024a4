"""Conversions to and from Open3D, when it is installed (skipped, saying so, when not)."""

import numpy as np
import pytest

import pdd

o3d = pytest.importorskip("open3d", reason="open3d is not installed (Debian: python3-open3d)")


def test_point_cloud_and_mesh_round_trips(sphere, sphere_mesh):
    cloud = pdd.PointCloud(*sphere).to_open3d()
    assert isinstance(cloud, o3d.geometry.PointCloud) and cloud.has_normals()
    back = pdd.PointCloud.from_open3d(cloud)
    np.testing.assert_array_equal(back.points, sphere[0])
    np.testing.assert_array_equal(back.normals, sphere[1])

    mesh = sphere_mesh.to_open3d()
    assert isinstance(mesh, o3d.geometry.TriangleMesh)
    assert mesh.is_edge_manifold() and mesh.is_vertex_manifold()
    assert len(mesh.triangles) == len(sphere_mesh.faces)
    again = pdd.Mesh.from_open3d(mesh)
    np.testing.assert_array_equal(again.vertices, sphere_mesh.vertices)
    np.testing.assert_array_equal(again.faces, sphere_mesh.faces)


def test_open3d_objects_go_straight_in(sphere):
    cloud = pdd.PointCloud(*sphere).to_open3d()
    mesh = pdd.reconstruct(cloud, target_edge=0.2, threads=2)
    assert pdd.quality(mesh.to_open3d())["surface"]["closed"]
