"""pdd.reconstruct on numpy arrays: the surface, the array types, determinism."""

import numpy as np
import pytest

import pdd
from conftest import EDGE, fibonacci_sphere


def radial_error(mesh):
    return np.abs(np.linalg.norm(mesh.vertices, axis=1) - 1.0)


def test_sphere_from_arrays_is_closed_and_close_to_the_truth(sphere_mesh):
    assert sphere_mesh.vertices.dtype == np.float64 and sphere_mesh.vertices.shape[1] == 3
    assert sphere_mesh.faces.dtype == np.int32 and sphere_mesh.faces.shape[1] == 3
    assert len(sphere_mesh.faces) > 1000
    report = pdd.quality(sphere_mesh)
    surface = report["surface"]
    assert surface["closed"] and surface["manifold"]
    assert surface["components"] == 1 and surface["genus"] == 0
    assert radial_error(sphere_mesh).max() < 0.01
    assert report["triangles"]["mean_min_angle"] > 35


def test_float32_float64_and_non_contiguous_arrays_give_the_same_mesh(sphere):
    points, normals = sphere
    reference = pdd.reconstruct(points, normals, target_edge=EDGE, threads=2)
    # A strided view of a wider array, and Fortran order: read through the strides.
    wide = np.zeros((len(points), 6))
    wide[:, ::2] = points
    strided = wide[:, ::2]
    assert not strided.flags.c_contiguous
    for p, n in [(strided, np.asfortranarray(normals)), (points.tolist(), normals.tolist())]:
        mesh = pdd.reconstruct(p, n, target_edge=EDGE, threads=2)
        np.testing.assert_array_equal(mesh.vertices, reference.vertices)
        np.testing.assert_array_equal(mesh.faces, reference.faces)
    # float32 rounds the input: a different but equally good sphere.
    single = pdd.reconstruct(points.astype(np.float32), normals.astype(np.float32),
                            target_edge=EDGE, threads=2)
    assert pdd.quality(single)["surface"]["genus"] == 0
    assert radial_error(single).max() < 0.01


def test_the_same_seed_gives_identical_arrays_and_another_seed_another_mesh(sphere):
    a = pdd.reconstruct(*sphere, seed=3, target_edge=EDGE, threads=2)
    b = pdd.reconstruct(*sphere, seed=3, target_edge=EDGE, threads=1)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    np.testing.assert_array_equal(a.faces, b.faces)
    c = pdd.reconstruct(*sphere, seed=4, target_edge=EDGE, threads=2)
    assert a.vertices.shape != c.vertices.shape or not np.array_equal(a.vertices, c.vertices)


def test_options_change_the_run(sphere):
    coarse = pdd.reconstruct(*sphere, target_edge=0.2, threads=2)
    fine = pdd.reconstruct(*sphere, target_edge=0.08, threads=2)
    assert len(fine.faces) > 3 * len(coarse.faces)
    raw = pdd.reconstruct(*sphere, target_edge=0.2, no_cleanup=True, solver="poisson",
                          iterations=3, threads=2)
    assert raw.stats["solver"] == "poisson"
    assert len(raw.stats["iterations"]) <= 4
    assert raw.stats["iterations"][-1]["cleanup_flips"] == 0


def test_a_point_cloud_object_and_its_own_normals(sphere):
    cloud = pdd.PointCloud(*sphere)
    mesh = pdd.reconstruct(cloud, target_edge=0.2, threads=2)
    assert pdd.quality(mesh)["surface"]["closed"]


def test_progress_reports_stages_and_false_cancels(sphere):
    seen = []

    def record(p):
        seen.append((p.stage, p.iteration, p.vertices, p.elapsed_seconds))

    pdd.reconstruct(*sphere, target_edge=0.2, progress=record, threads=2)
    stages = {s for s, *_ in seen}
    assert {"solve", "contour"} <= stages
    assert all(b[3] >= a[3] for a, b in zip(seen, seen[1:]))  # time moves forward
    assert max(v for *_, v, _ in seen) > 100

    calls = []

    def stop_at_first_solve(p):
        calls.append(p.stage)
        return p.stage != "solve"

    with pytest.raises(pdd.Cancelled):
        pdd.reconstruct(*sphere, progress=stop_at_first_solve, target_edge=EDGE,
                        threads=2)
    assert calls[-1] == "solve" and calls.count("solve") == 1


def test_an_exception_in_the_callback_stops_the_run_and_is_raised(sphere):
    def fail(p):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        pdd.reconstruct(*sphere, progress=fail, target_edge=EDGE)


def test_ctrl_c_cancels_through_the_progress_callback(sphere):
    import signal

    def interrupt(p):
        if p.stage == "optimize":
            signal.raise_signal(signal.SIGINT)  # Python's handler: KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        pdd.reconstruct(*sphere, progress=interrupt, target_edge=EDGE, threads=2)


def test_two_spheres_give_two_components():
    a, na = fibonacci_sphere(1500, 1.0, (0, 0, 0))
    b, nb = fibonacci_sphere(1500, 1.0, (3, 0, 0))
    mesh = pdd.reconstruct(np.vstack([a, b]), np.vstack([na, nb]), target_edge=EDGE,
                           threads=2)
    assert pdd.quality(mesh)["surface"]["components"] == 2


def test_domain_out_and_save_iterations_write_files(sphere, tmp_path):
    pdd.reconstruct(*sphere, target_edge=0.25, domain_out=tmp_path / "domain.vtu",
                    save_iterations=tmp_path / "iterations", threads=2)
    assert (tmp_path / "domain.vtu").stat().st_size > 1000
    assert len(list((tmp_path / "iterations").glob("iteration_*_isosurface.ply"))) >= 2


def test_a_real_sigint_stops_a_run_without_a_callback(tmp_path):
    """Ctrl-C in a terminal: Python's handler sets a flag while the library runs with the
    GIL released; the module's own progress hook raises KeyboardInterrupt at the next stage."""
    import os
    import subprocess
    import sys
    import time

    script = tmp_path / "run.py"
    script.write_text(
        "import sys, pdd\n"
        "sys.path.insert(0, %r)\n"
        "from conftest import fibonacci_sphere\n"
        "points, normals = fibonacci_sphere(4000)\n"
        "print('started', flush=True)\n"
        "pdd.reconstruct(points, normals, target_edge=0.01, threads=1)\n"
        "print('finished', flush=True)\n" % os.path.dirname(__file__))
    child = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "started\n"
    time.sleep(1.5)
    child.send_signal(2)
    sent = time.monotonic()
    out, err = child.communicate(timeout=60)
    assert time.monotonic() - sent < 10  # the longest stage of this run is about a second
    assert child.returncode != 0 and "finished" not in out
    assert "KeyboardInterrupt" in err


def test_points_without_normals_and_flipped_normals(sphere, sphere_mesh):
    points, normals = sphere
    with pytest.warns(UserWarning, match="normals estimated by jet fitting"):
        bare = pdd.reconstruct(points, target_edge=EDGE, threads=2)
    assert bare.stats["normals"]["estimated"] and bare.stats["normals"]["oriented"]
    assert pdd.quality(bare)["surface"]["genus"] == 0
    # Estimated normals: max 0.0103, mean 0.00054 (with the true normals 0.0079 and 0.00054)
    assert radial_error(bare).max() < 0.015 and radial_error(bare).mean() < 0.001
    flipped = normals * np.where(np.arange(len(normals)) % 2 == 0, -1.0, 1.0)[:, None]
    again = pdd.reconstruct(points, flipped, normals_mode="orient", target_edge=EDGE, threads=2)
    np.testing.assert_array_equal(again.vertices, sphere_mesh.vertices)
    cloud = pdd.estimate_normals(points)
    assert cloud.normals.shape == points.shape
    assert np.all(np.sum(cloud.normals * points, axis=1) > 0.99)  # unit, outward


def test_an_open_sheet_and_a_trimmed_run_say_so(sphere):
    # Notes as the command line prints them: an output that runs into the
    # domain's boundary is open, and a trimmed one says what it cut.
    points, normals = sphere
    upper = points[:, 2] > 0.3
    up = np.tile([0.0, 0.0, 1.0], (upper.sum(), 1))  # a sheet facing up: no inside
    with pytest.warns(UserWarning, match="the output is open"):
        sheet = pdd.reconstruct(points[upper], up, target_edge=EDGE, threads=2)
    assert sheet.stats["iterations"][-1]["boundary_edges"] > 0
    with pytest.warns(UserWarning, match="trimmed to the samples"):
        pdd.reconstruct(points[upper], normals[upper], trim=2, target_edge=EDGE, threads=2)

