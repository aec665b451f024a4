# Type stub of the package pdd, for editors and type checkers. The options of
# reconstruct are those of `pdd reconstruct` (python/tests/test_api.py checks
# that this file lists them all with the module's defaults).
from os import PathLike
from typing import Any, Callable, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Path = Union[str, PathLike[str]]

class Cancelled(Exception): ...

class Progress:
    @property
    def stage(self) -> str: ...
    @property
    def iteration(self) -> int: ...
    @property
    def vertices(self) -> int: ...
    @property
    def elapsed_seconds(self) -> float: ...

class PointCloud:
    points: npt.NDArray[Any]
    normals: Optional[npt.NDArray[Any]]
    colors: Optional[npt.NDArray[Any]]
    attributes: dict[str, npt.NDArray[Any]]
    def __init__(self, points: ArrayLike, normals: Optional[ArrayLike] = None,
                 colors: Optional[ArrayLike] = None,
                 attributes: Optional[dict[str, ArrayLike]] = None) -> None: ...
    def __len__(self) -> int: ...
    def to_open3d(self) -> Any: ...
    @classmethod
    def from_open3d(cls, cloud: Any) -> PointCloud: ...

class Mesh:
    vertices: npt.NDArray[Any]
    faces: npt.NDArray[Any]
    stats: Optional[dict[str, Any]]
    colors: Optional[npt.NDArray[Any]]
    attributes: dict[str, npt.NDArray[Any]]
    def __init__(self, vertices: ArrayLike, faces: ArrayLike,
                 stats: Optional[dict[str, Any]] = None, colors: Optional[ArrayLike] = None,
                 attributes: Optional[dict[str, ArrayLike]] = None) -> None: ...
    def to_open3d(self) -> Any: ...
    @classmethod
    def from_open3d(cls, mesh: Any) -> Mesh: ...

MeshLike = Union[Mesh, tuple[ArrayLike, ArrayLike], Any]

def reconstruct(
    points: Union[ArrayLike, PointCloud, Any],
    normals: Optional[ArrayLike] = None,
    colors: Optional[ArrayLike] = None,
    *,
    solver: Literal["ssd", "poisson", "spectral"] = "ssd",
    normals_mode: Literal["keep", "orient", "estimate"] = "keep",
    orientation: Literal["visibility", "spectral", "mst"] = "visibility",
    normal_neighbors: int = 18,
    outliers: float = 3.0,
    value_weight: Optional[float] = None,
    linear: Literal["multigrid", "cholmod"] = "multigrid",
    domain: Literal["progressive", "direct", "input", "octree"] = "progressive",
    sizing: Literal["uniform", "adaptive"] = "uniform",
    target_edge: Optional[float] = None,
    target_area: Optional[float] = None,
    target_faces: int = 0,
    tolerance: Optional[float] = None,
    gradation: float = 1.0,
    iterations: int = 12,
    max_memory: Optional[Union[int, str]] = None,
    optimizer_rounds: int = 2,
    optimizer_rounds_before_refining: int = 1,
    hole_coarsening: float = 4.0,
    min_component_size: float = 4.0,
    min_component_samples: int = 10,
    trim: float = 0.0,
    trim_holes: float = 30.0,
    trim_islands: float = 10.0,
    attributes: str = "colors",
    keep_handles: bool = False,
    no_cleanup: bool = False,
    cleanup_dihedral: float = 30.0,
    threads: int = 0,
    enlarge_ratio: float = 1.4,
    sphere_points: int = 100,
    radius_edge: float = 1.3,
    lambda_asap: float = 60.0,
    lambda_mid_edge: float = 3.0,
    damping: float = 100.0,
    seed: int = 0,
    progress: Optional[Callable[[Progress], Optional[bool]]] = None,
    domain_out: Optional[Path] = None,
    save_iterations: Optional[Path] = None,
) -> Mesh: ...
def estimate_normals(points: Union[ArrayLike, PointCloud, Any], normals: Optional[ArrayLike] = None,
                     *, normals_mode: Literal["keep", "orient", "estimate"] = "keep",
                     orientation: Literal["visibility", "spectral", "mst"] = "visibility", normal_neighbors: int = 18,
                     threads: int = 0) -> PointCloud: ...
def find_outliers(points: Union[ArrayLike, PointCloud, Any], *, ratio: float = 3.0,
                  neighbors: int = 16) -> npt.NDArray[np.bool_]: ...
def read_points(path: Path) -> PointCloud: ...
def read_mesh(path: Path) -> Mesh: ...
def write_mesh(path: Path, mesh: MeshLike, *, ascii: bool = False) -> None: ...
def quality(mesh: MeshLike) -> dict[str, Any]: ...
def compare(a: MeshLike, b: MeshLike, *, samples: int = 200000,
            fscore_threshold: float = 0.005, seed: int = 0) -> dict[str, Any]: ...
