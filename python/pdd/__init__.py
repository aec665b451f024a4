"""pdd: closed triangle meshes from point clouds by progressive discrete domains.

Zhao, Alliez, Boubekeur, Busé, Thiery, SGP 2021. A thin client of the same
C++ library as the command line `pdd`:

    import numpy as np, pdd
    mesh = pdd.reconstruct(points, normals)          # (n, 3) arrays
    mesh.vertices, mesh.faces, mesh.stats            # (v, 3) float64, (f, 3) int32, dict
    pdd.write_mesh("out.ply", mesh)
    pdd.quality(mesh)["surface"]["genus"]

Every option of `pdd reconstruct` is a keyword argument of `reconstruct` with
the same name (dashes as underscores) and default. Bad input or options raise
ValueError, a failed solve RuntimeError, with the command line's messages.
"""

from __future__ import annotations

import inspect
import json
import numbers
import textwrap
import warnings

import numpy as np

from . import _pdd
from ._pdd import Progress

__version__ = _pdd.__version__
__all__ = [
    "Cancelled",
    "Mesh",
    "PointCloud",
    "Progress",
    "compare",
    "estimate_normals",
    "find_outliers",
    "quality",
    "read_mesh",
    "read_points",
    "reconstruct",
    "write_mesh",
]


class Cancelled(Exception):
    """A reconstruction stopped because its progress callback returned False."""


def _open3d():
    try:
        import open3d
    except ImportError as error:
        raise ImportError(
            "open3d is not installed (Debian: apt install python3-open3d); "
            "pdd does not need it, only its Open3D conversions do"
        ) from error
    return open3d


def _is_open3d(obj) -> bool:
    return type(obj).__module__.split(".")[0] == "open3d"


# Attributes cross into the library as (name, PLY type, values); colours are the
# channels red, green, blue (alpha), uint8 0-255 or floats 0-1.
_TYPES = {"char": np.int8, "uchar": np.uint8, "short": np.int16, "ushort": np.uint16,
          "int": np.int32, "uint": np.uint32, "float": np.float32, "double": np.float64}
_COLOURS = ("red", "green", "blue", "alpha")


def _ply_type(values: np.ndarray, what: str) -> str:
    for name, dtype in _TYPES.items():
        if values.dtype == np.dtype(dtype):
            return name
    if np.issubdtype(values.dtype, np.floating):
        return "double"
    if np.issubdtype(values.dtype, np.integer) and np.bool_(
            values.size == 0 or (values.min() >= -2**31 and values.max() < 2**31)):
        return "int"
    raise ValueError(f"{what}: expected numbers that a PLY property holds (up to 32-bit "
                     f"integers or floats), got dtype {values.dtype}")


def _to_native(colors, attributes) -> list:
    entries = []
    if colors is not None:
        c = np.asarray(colors)
        if c.ndim != 2 or c.shape[1] not in (3, 4):
            raise ValueError(f"colors: expected an array of shape (n, 3) or (n, 4), "
                             f"got shape {c.shape}")
        if c.dtype == np.uint8:
            kind = "uchar"
        elif c.dtype == np.uint16:
            kind = "ushort"
        elif np.issubdtype(c.dtype, np.floating):
            kind = "float" if c.dtype == np.float32 else "double"
        else:
            raise ValueError(f"colors: expected uint8 (0-255), uint16 or floats (0-1), "
                             f"got dtype {c.dtype}")
        entries += [(_COLOURS[k], kind, c[:, k]) for k in range(c.shape[1])]
    for name, values in (attributes or {}).items():
        if name in _COLOURS:
            raise ValueError(f"attributes: {name!r} is a colour channel; pass colours as colors=")
        values = np.asarray(values)
        entries.append((str(name), _ply_type(values, str(name)), values))
    return entries


def _from_native(entries):
    """(colors, attributes) from the library's (name, type, float64 values) list."""
    channels = {name: (kind, values) for name, kind, values in entries if name in _COLOURS}
    colors = None
    if channels:
        dtype = _TYPES[channels["red"][0]]
        colors = np.stack([channels[c][1] for c in _COLOURS if c in channels], axis=1)
        colors = colors.astype(dtype)
    attributes = {name: values.astype(_TYPES[kind])
                  for name, kind, values in entries if name not in _COLOURS}
    return colors, attributes


def _unit_colours(colors: np.ndarray) -> np.ndarray:
    if colors.dtype == np.uint8:
        return colors[:, :3] / 255.0
    if colors.dtype == np.uint16:
        return colors[:, :3] / 65535.0
    return np.asarray(colors[:, :3], dtype=np.float64)


class PointCloud:
    """Points (n, 3) and, when known, their normals (n, 3), colours (n, 3) or (n, 4)
    (uint8 0-255 or floats 0-1) and other per-point properties (`attributes`: name ->
    (n,) array), as numpy arrays."""

    def __init__(self, points, normals=None, colors=None, attributes=None):
        self.points = np.asarray(points)
        self.normals = None if normals is None else np.asarray(normals)
        self.colors = None if colors is None else np.asarray(colors)
        self.attributes = dict(attributes or {})

    def __len__(self) -> int:
        return len(self.points)

    def __repr__(self) -> str:
        extra = ", colours" if self.colors is not None else ""
        extra += "".join(f", {name}" for name in self.attributes)
        return (f"PointCloud({len(self)} points, "
                f"{'with' if self.normals is not None else 'no'} normals{extra})")

    def to_open3d(self):
        """This point cloud as an open3d.geometry.PointCloud (needs open3d)."""
        o3d = _open3d()
        cloud = o3d.geometry.PointCloud(
            o3d.utility.Vector3dVector(np.asarray(self.points, dtype=np.float64)))
        if self.normals is not None:
            cloud.normals = o3d.utility.Vector3dVector(np.asarray(self.normals, dtype=np.float64))
        if self.colors is not None:
            cloud.colors = o3d.utility.Vector3dVector(_unit_colours(self.colors))
        return cloud

    @classmethod
    def from_open3d(cls, cloud) -> "PointCloud":
        """The points, normals and colours (those it has) of an open3d.geometry.PointCloud."""
        normals = np.asarray(cloud.normals) if cloud.has_normals() else None
        colors = np.asarray(cloud.colors) if cloud.has_colors() else None
        return cls(np.asarray(cloud.points), normals, colors)


class Mesh:
    """A triangle mesh: vertices (n, 3), faces (m, 3) indexing them, counter-clockwise
    seen from outside; per-vertex colours (n, 3) or (n, 4) and other `attributes`
    (name -> (n,) array) where the input carried them. A reconstruction's mesh has
    float64 vertices, int32 faces and `stats`, the run's statistics (the content of
    `pdd reconstruct --stats`)."""

    def __init__(self, vertices, faces, stats=None, colors=None, attributes=None):
        self.vertices = np.asarray(vertices)
        self.faces = np.asarray(faces)
        self.stats = stats
        self.colors = None if colors is None else np.asarray(colors)
        self.attributes = dict(attributes or {})

    def __repr__(self) -> str:
        extra = ", colours" if self.colors is not None else ""
        return f"Mesh({len(self.vertices)} vertices, {len(self.faces)} faces{extra})"

    def to_open3d(self):
        """This mesh as an open3d.geometry.TriangleMesh (needs open3d), with its colours."""
        o3d = _open3d()
        mesh = o3d.geometry.TriangleMesh(
            o3d.utility.Vector3dVector(np.asarray(self.vertices, dtype=np.float64)),
            o3d.utility.Vector3iVector(np.asarray(self.faces, dtype=np.int32)))
        if self.colors is not None:
            mesh.vertex_colors = o3d.utility.Vector3dVector(_unit_colours(self.colors))
        return mesh

    @classmethod
    def from_open3d(cls, mesh) -> "Mesh":
        """The vertices, triangles and vertex colours of an open3d.geometry.TriangleMesh."""
        colors = np.asarray(mesh.vertex_colors) if mesh.has_vertex_colors() else None
        return cls(np.asarray(mesh.vertices), np.asarray(mesh.triangles), colors=colors)


def _as_mesh(mesh, what: str) -> Mesh:
    if isinstance(mesh, Mesh):
        return mesh
    if _is_open3d(mesh):
        return Mesh.from_open3d(mesh)
    if isinstance(mesh, tuple) and len(mesh) == 2:
        return Mesh(*mesh)
    raise ValueError(f"{what}: expected a pdd.Mesh, an open3d TriangleMesh or a "
                     f"(vertices, faces) tuple, got {type(mesh).__name__}")


# ------------------------------------------------------------------ options

# Python names of the command line's options: dashes as underscores; `--normals` (what to do
# with the input's normals) is `normals_mode`, since `normals` is the array itself.
_RENAMED = {"normals": "normals_mode"}
_SPECS = {_RENAMED.get(spec["name"], spec["name"].replace("-", "_")): spec
          for spec in _pdd.option_specs()}


def _default(spec):
    text, kind = spec["default"], spec["kind"]
    if text == "":
        return None  # derived from the input; the help says how
    if kind == "flag":
        return text == "true"
    if kind in ("integer", "seed"):
        return int(text)
    if kind == "number":
        return float(text)
    return text


def _option_text(name: str, spec, value) -> str:
    """The option's value as the command line would spell it; the library parses it."""
    kind = spec["kind"]
    is_bool = isinstance(value, (bool, np.bool_))
    if kind == "flag" and is_bool:
        return "true" if value else "false"
    if kind == "choice" and isinstance(value, str):
        return value
    if kind in ("integer", "seed", "size") and isinstance(value, numbers.Integral) and not is_bool:
        return str(int(value))
    if kind == "number" and isinstance(value, numbers.Real) and not is_bool:
        return repr(float(value))
    if kind in ("size", "text") and isinstance(value, str):
        return value
    expected = {"flag": "True or False", "choice": "one of " + ", ".join(spec["choices"]),
                "integer": "an integer", "seed": "an integer", "number": "a number",
                "size": "a number of bytes or a size such as '8G'", "text": "a string"}[kind]
    raise ValueError(f"--{spec['name']}: must be {expected}, got {value!r}")


def reconstruct(points, normals=None, colors=None, *, progress=None, domain_out=None,
                save_iterations=None, **options) -> Mesh:
    # The signature and the docstring are set below from the library's option table.
    points, normals, colors, attributes = _as_points(points, normals, colors)
    pairs = []
    for name, value in options.items():
        spec = _SPECS.get(name)
        if spec is None:
            raise TypeError(f"reconstruct() got an unexpected keyword argument {name!r}")
        if value is not None:
            pairs.append((spec["name"], _option_text(name, spec, value)))
    if progress is not None and not callable(progress):
        raise ValueError(f"progress: expected a callable or None, got {type(progress).__name__}")
    result = _pdd.reconstruct(points, normals, _to_native(colors, attributes), pairs, progress,
                              "" if domain_out is None else str(domain_out),
                              "" if save_iterations is None else str(save_iterations))
    for warning in result["warnings"]:
        warnings.warn(warning, stacklevel=2)
    if result["cancelled"]:
        raise Cancelled("the progress callback returned False: the run stopped, no mesh")
    for note in result["notes"]:
        warnings.warn(note, stacklevel=2)
    colors, attributes = _from_native(result["attributes"])
    return Mesh(result["vertices"], result["faces"], json.loads(result["stats"]), colors,
                attributes)


def _reconstruct_docstring() -> str:
    lines = [
        "Reconstructs a closed triangle mesh from points and normals (§3 of the paper).",
        "",
        "points: (n, 3) array of float64 or float32 (any strides), a pdd.PointCloud or an",
        "    open3d PointCloud. normals: (n, 3) array or None (then the points' own).",
        "colors: (n, 3) or (n, 4) array, uint8 (0-255) or floats (0-1), or None (then the",
        "    points' own); carried to the output's vertices (see `attributes`).",
        "Returns a pdd.Mesh with vertices (float64), faces (int32), stats (dict), and colors",
        "    and attributes where the run carried them.",
        "",
        "progress: called between stages with a pdd.Progress (stage, iteration, vertices,",
        "    elapsed_seconds); returning False stops the run and raises pdd.Cancelled.",
        "    Ctrl-C stops it too (KeyboardInterrupt), at the next stage.",
        "domain_out: also write the final domain with f as a .vtu (ParaView).",
        "save_iterations: a folder for every iteration's isosurface and domain.",
        "",
        "Options (as `pdd reconstruct --OPTION`; None keeps the default):",
    ]
    for name, spec in _SPECS.items():
        default = _default(spec)
        shown = "None: chosen by the run" if default is None else repr(default)
        if spec["choices"]:
            shown += "; one of " + ", ".join(spec["choices"])
        lines += textwrap.wrap(f"{name} ({shown}): {spec['help']}", 88,
                               initial_indent="  ", subsequent_indent="      ")
    lines += ["", "Raises ValueError for bad input or options, RuntimeError for a failed solve."]
    return "\n".join(lines)


reconstruct.__doc__ = _reconstruct_docstring()
reconstruct.__signature__ = inspect.Signature(
    [inspect.Parameter("points", inspect.Parameter.POSITIONAL_OR_KEYWORD),
     inspect.Parameter("normals", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None),
     inspect.Parameter("colors", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None)]
    + [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=_default(spec))
       for name, spec in _SPECS.items()]
    + [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None)
       for name in ("progress", "domain_out", "save_iterations")],
    return_annotation=Mesh)


def _as_points(points, normals, colors=None):
    """(points, normals, colors, attributes) from arrays, a pdd.PointCloud or an open3d
    PointCloud; arguments given explicitly win over the cloud's own."""
    if _is_open3d(points):
        points = PointCloud.from_open3d(points)
    if isinstance(points, PointCloud):
        return (points.points, points.normals if normals is None else normals,
                points.colors if colors is None else colors, points.attributes)
    return points, normals, colors, {}


def estimate_normals(points, normals=None, *,
                     normals_mode: str = _default(_SPECS["normals_mode"]),
                     orientation: str = _default(_SPECS["orientation"]),
                     normal_neighbors: int = _default(_SPECS["normal_neighbors"]),
                     threads: int = 0) -> PointCloud:
    """The normals a reconstruction would use, as `pdd normals` writes them: missing ones
    estimated by jet fitting and oriented; normals_mode="orient" re-orients given ones,
    "estimate" replaces them (as in reconstruct). Returns a pdd.PointCloud."""
    points, normals, _, _ = _as_points(points, normals)
    pairs = [(_SPECS[name]["name"], _option_text(name, _SPECS[name], value)) for name, value in
             [("normals_mode", normals_mode), ("orientation", orientation),
              ("normal_neighbors", normal_neighbors), ("threads", threads)]]
    p, n, _, _ = _pdd.prepare_normals(points, normals, pairs)
    return PointCloud(p, n)


# ----------------------------------------------------------- files, metrics

def read_points(path) -> PointCloud:
    """Reads a point set (.ply .xyz .pwn .xyzn .off .obj) as `pdd reconstruct` does: the
    same checks and messages (ValueError); exact duplicates merged, with a warning. A
    PLY's colours and other vertex properties come as `colors` and `attributes`."""
    points, normals, notes, entries = _pdd.read_points(str(path))
    for note in notes:
        warnings.warn(note, stacklevel=2)
    return PointCloud(points, normals, *_from_native(entries))


def read_mesh(path) -> Mesh:
    """Reads a triangle mesh (.ply .off .obj); ValueError naming the file when it is bad."""
    vertices, faces, entries = _pdd.read_mesh(str(path))
    colors, attributes = _from_native(entries)
    return Mesh(vertices, faces, colors=colors, attributes=attributes)


def write_mesh(path, mesh, *, ascii: bool = False) -> None:
    """Writes a mesh (.ply .off .obj, by the extension) atomically: the file appears whole
    or not at all. PLY vertices are written as doubles (exact round trip), then the
    colours and attributes in their types; OFF and OBJ carry the colours only.
    ascii=True writes a text PLY."""
    mesh = _as_mesh(mesh, "mesh")
    _pdd.write_mesh(str(path), mesh.vertices, mesh.faces,
                    _to_native(mesh.colors, mesh.attributes), bool(ascii))


def find_outliers(points, *, ratio: float = _default(_SPECS["outliers"]),
                  neighbors: int = 16) -> np.ndarray:
    """The outlier test a reconstruction runs first (option `outliers`): a boolean mask,
    True for the points whose mean distance to their `neighbors` nearest points exceeds
    `ratio` times that of those neighbours. ratio=0 finds none."""
    points, _, _, _ = _as_points(points, None)
    return _pdd.find_outliers(points, float(ratio), int(neighbors))


def quality(mesh) -> dict:
    """Triangle quality and surface checks, the content of `pdd quality --json`:
    {"vertices", "faces", "triangles": {angles, histogram}, "surface": {manifold,
    closed, components, genus, ...}}."""
    mesh = _as_mesh(mesh, "mesh")
    report = json.loads(_pdd.quality(mesh.vertices, mesh.faces))
    del report["file"]
    return report


_COMPARE = _pdd.compare_defaults()  # those of `pdd compare`


def compare(a, b, *, samples: int = _COMPARE["samples"],
            fscore_threshold: float = _COMPARE["fscore_threshold"],
            seed: int = _COMPARE["seed"]) -> dict:
    """Two-sided distances between meshes a and b (b the reference), the content of
    `pdd compare --json`: Hausdorff, Chamfer-L1, means, RMS, F-score, each also relative
    to b's bounding-box diagonal (keys ending in _relative)."""
    a, b = _as_mesh(a, "a"), _as_mesh(b, "b")
    most = _COMPARE["max_samples"]
    if (isinstance(samples, bool) or not isinstance(samples, numbers.Integral) or samples < 1
            or samples > most):
        raise ValueError(f"samples: must be an integer from 1 to {most}, got {samples!r}")
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
        raise ValueError(f"seed: must be an integer >= 0, got {seed!r}")
    report = json.loads(_pdd.compare(a.vertices, a.faces, b.vertices, b.faces, int(samples),
                                     float(fscore_threshold), int(seed)))
    del report["a"], report["b"]
    return report
