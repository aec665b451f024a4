"""Shared fixtures: generated analytic shapes (no data outside the repository)."""

import os
import pathlib

import numpy as np
import pytest


def fibonacci_sphere(n, radius=1.0, center=(0.0, 0.0, 0.0)):
    """n points spread evenly on a sphere and their outward unit normals."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    r = np.sqrt(1 - z * z)
    phi = i * np.pi * (3 - np.sqrt(5))
    normals = np.column_stack([r * np.cos(phi), r * np.sin(phi), z])
    return np.asarray(center) + radius * normals, normals


# A target edge that keeps the tests' meshes small (about 6000 triangles on the unit sphere).
EDGE = 0.06


@pytest.fixture(scope="session")
def sphere():
    return fibonacci_sphere(2000)


@pytest.fixture(scope="session")
def sphere_mesh(sphere):
    import pdd
    return pdd.reconstruct(*sphere, target_edge=EDGE, threads=2)


@pytest.fixture(scope="session")
def pdd_binary():
    return os.environ["PDD_BINARY"]


@pytest.fixture(scope="session")
def source_dir():
    return pathlib.Path(os.environ["PDD_SOURCE_DIR"])
