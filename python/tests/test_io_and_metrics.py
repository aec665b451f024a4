"""Files, quality and compare through Python, against the command line."""

import json
import subprocess

import numpy as np
import pytest

import pdd


def test_write_and_read_mesh_round_trip(sphere_mesh, tmp_path):
    for name, ascii in [("m.ply", False), ("m_text.ply", True), ("m.obj", False), ("m.off", False)]:
        pdd.write_mesh(tmp_path / name, sphere_mesh, ascii=ascii)
        back = pdd.read_mesh(tmp_path / name)
        np.testing.assert_array_equal(back.faces, sphere_mesh.faces)
        np.testing.assert_array_equal(back.vertices, sphere_mesh.vertices)  # exact doubles


def test_read_points_as_the_command_line_reads_them(source_dir):
    cloud = pdd.read_points(source_dir / "data" / "kitten_scan.ply")
    assert cloud.points.shape == cloud.normals.shape and len(cloud) > 5000
    assert cloud.points.dtype == np.float64


def test_stats_match_the_command_line_json(source_dir, pdd_binary, tmp_path):
    """The same input and options give the same run through both clients."""
    scan = source_dir / "data" / "kitten_scan.ply"
    options = ["--target-edge", "0.05", "--iterations", "4", "--seed", "2"]
    subprocess.run([pdd_binary, "reconstruct", str(scan), "-o", str(tmp_path / "cli.ply"),
                    "--stats", str(tmp_path / "cli.json"), "--quiet", *options], check=True)
    cli = json.loads((tmp_path / "cli.json").read_text())
    mesh = pdd.reconstruct(pdd.read_points(scan), target_edge=0.05, iterations=4, seed=2)

    def without_times(stats):
        stats = dict(stats, seconds=None, memory_budget=None)
        stats["iterations"] = [dict(i, seconds=None) for i in stats["iterations"]]
        return stats

    assert without_times(mesh.stats) == without_times(cli)
    written = pdd.read_mesh(tmp_path / "cli.ply")
    np.testing.assert_array_equal(written.vertices, mesh.vertices)
    np.testing.assert_array_equal(written.faces, mesh.faces)


def test_quality_and_compare_match_the_command_line(sphere_mesh, pdd_binary, tmp_path):
    pdd.write_mesh(tmp_path / "a.ply", sphere_mesh)
    cli = json.loads(subprocess.run([pdd_binary, "quality", str(tmp_path / "a.ply"), "--json"],
                                    check=True, capture_output=True, text=True).stdout)
    del cli["file"]
    assert pdd.quality(sphere_mesh) == cli

    shifted = pdd.Mesh(sphere_mesh.vertices * 1.01, sphere_mesh.faces)
    pdd.write_mesh(tmp_path / "b.ply", shifted)
    cli = json.loads(subprocess.run(
        [pdd_binary, "compare", str(tmp_path / "a.ply"), str(tmp_path / "b.ply"), "--json",
         "--samples", "20000"], check=True, capture_output=True, text=True).stdout)
    ours = pdd.compare(sphere_mesh, shifted, samples=20000)
    del cli["a"], cli["b"]
    assert ours == cli
    assert ours["chamfer_l1"] == pytest.approx(0.01, rel=0.1)  # a 1 % larger unit sphere


def test_compare_defaults_are_the_command_line_s(pdd_binary):
    help_text = subprocess.run([pdd_binary, "compare", "--help"], check=True,
                               capture_output=True, text=True).stdout
    import inspect
    params = inspect.signature(pdd.compare).parameters
    assert f"={params['samples'].default}" in help_text
    assert f"={params['fscore_threshold'].default}" in help_text
