// File formats: point sets in, triangle meshes and domains out (DESIGN.md,
// stage "io"). Every reader reports bad input as pdd::InputError with a
// message that starts with the file's path and names the line, the record or
// the value at fault. Every writer is atomic: it writes to a temporary file in
// the target folder and renames it on success, so that a failed write never
// leaves a partial or empty file behind.
//
// Formats are chosen by the file's extension, case-insensitively:
//   points in:   .ply  .xyz .pwn .xyzn  .off  .obj
//   points out:  .ply  .xyz .pwn .xyzn  .off  .obj
//   meshes:      .ply  .off  .obj       (read and write)
//   domains out: .vtu                   (VTK XML UnstructuredGrid, ParaView)
#pragma once

#include <pdd/types.h>

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <mutex>
#include <string>
#include <vector>

namespace pdd {

// ---------------------------------------------------------------- points in

// Checks applied to every point set read from a file (and available for point
// sets built in memory through validate_points).
// Every test is on the points' own extent, wherever they are: a scan in
// georeferenced coordinates (millions of units from the origin) passes as it
// would at the origin.
struct ValidationOptions {
  std::size_t min_points = 4;  // fewer distinct points cannot enclose a volume
  // A point set whose thickness (extent along its thinnest direction) is at
  // most flatness_tolerance * (bounding-box diagonal) is rejected as coplanar.
  // 1e-6 is well above the rounding of float32 files, so a plane stored as
  // floats is caught.
  double flatness_tolerance = 1e-6;
  // One whose bounding-box diagonal is at most coincidence_tolerance * (its
  // largest absolute coordinate) is rejected as coincident: its points differ
  // by little more than the rounding of their coordinates, and so would the
  // output's vertices.
  double coincidence_tolerance = 1e-12;
  // The bounding-box diagonals the reconstruction computes with: beyond
  // them, powers of lengths (tet volumes, squared areas) overflow or
  // underflow a double.
  double min_extent = 1e-50;
  double max_extent = 1e50;
};

// What validation changed, for the caller to show the user.
struct ValidationReport {
  std::size_t points_read = 0;  // points in the input, before merging
  // Points dropped because an earlier point has exactly the same position.
  std::size_t merged_duplicates = 0;
  // Of the merged duplicates, how many carried a normal different from the
  // kept (first) occurrence's.
  std::size_t merged_with_other_normal = 0;
  // Points whose normal is (0, 0, 0): no normal, as some scanners write it; kept,
  // and estimated by the reconstruction (fill_missing_normals, normals.h).
  std::size_t zero_normals = 0;
  std::string first_zero_normal;  // "line 12 (point 3)" or "point 3"
  // One line per remark, already phrased for the user ("kitten.ply: merged 3
  // duplicate points ..."); empty when there is nothing to say.
  std::vector<std::string> warnings;
};

// Reads a point set, with its normals when the file has them, and validates it
// (validate_points). Formats:
//   .ply              ASCII, binary_little_endian or binary_big_endian; element
//                     "vertex" with x y z and optionally nx ny nz of any scalar
//                     type; its other scalar properties become attributes
//                     (colours, intensity, labels); other elements are skipped.
//   .xyz .pwn .xyzn   text, one point per line: "x y z" or "x y z nx ny nz" (the
//                     same for every line); blank lines and text after '#' are
//                     skipped; an optional first line holding only the point
//                     count is checked against the points found.
//   .off              OFF / NOFF / COFF / CNOFF vertices (faces are not read).
//   .obj              "v" lines, and "vn" lines paired with them in order when
//                     there are exactly as many vn as v (any other count of vn
//                     is an error, since the pairing would be a guess).
// Throws InputError: missing or unreadable file, unknown extension, malformed
// header, truncated body, a line that does not parse (with its number), and
// every problem listed for validate_points.
PointSet read_points(const std::string& path, ValidationReport* report = nullptr,
                     const ValidationOptions& options = {});

// Validates a point set and returns it with exact duplicates merged (the first
// occurrence and its normal are kept; the report says how many were merged).
// Throws InputError, with a message starting with `source`, when a coordinate
// is NaN or infinite, a normal is not finite (a zero normal is taken as a
// missing one: counted and kept, for the reconstruction to estimate), there are
// fewer than options.min_points distinct points, or all points coincide, lie
// in one plane or span an extent out of range (see ValidationOptions); when a
// few far points (outliers) cause the last two, the message names them.
// Points are numbered from 1 in messages. Attributes are checked too: one
// value per point, and colours (red, green and blue together, optional alpha)
// of type uchar, ushort, float or double, and within 0-255, 0-65535 or 0-1.
// Normals are kept as given (not normalized).
PointSet validate_points(PointSet points, const std::string& source,
                         ValidationReport* report = nullptr, const ValidationOptions& options = {});

// Throws InputError, with a message starting with `source`, when `mesh` has no
// faces, a vertex coordinate that is not finite (vertices counted from 1) or a
// face that refers to a vertex it does not have (faces counted from 1).
// For meshes that come from memory (the Python module); read_mesh checks the
// same with the file's line numbers.
void validate_mesh(const TriangleMesh& mesh, const std::string& source);

// Throws InputError "<source>: the points have no normals; <why>" when `points`
// has none. Called by the command line and the solvers that need normals,
// e.g. why = "the SSD solver fits the gradient of f to oriented normals".
void require_normals(const PointSet& points, const std::string& source, const std::string& why);

// --------------------------------------------------------------- writing

class StagedOutputs;

struct PointWriteOptions {
  bool ascii = false;  // PLY only: ASCII instead of binary little-endian
};

// Writes a point set (with normals when it has them) in the format named by the
// extension: .ply (double x y z [nx ny nz]), .xyz/.pwn/.xyzn, .off (NOFF when
// there are normals), .obj (v and vn). Text numbers round-trip exactly.
void write_points(const std::string& path, const PointSet& points,
                  const PointWriteOptions& options = {});

struct MeshWriteOptions {
  bool ascii = false;  // PLY only: ASCII instead of binary little-endian
  // When set, the file is written into a temporary now and renamed onto
  // `path` by staged->commit(), with the run's other outputs.
  StagedOutputs* staged = nullptr;
};

// Writes a triangle mesh: .ply (vertices as double x y z so that positions
// round-trip bit for bit, then the attributes in their own types; faces as
// "list uchar int vertex_indices"), .off and .obj (colours only: COFF, and
// OBJ's "v x y z r g b"). Text numbers are written in their shortest form that reads back to
// the same double. Throws InputError for an unknown extension or a target that
// cannot be written, std::invalid_argument when a face refers to a vertex the
// mesh does not have.
void write_mesh(const std::string& path, const TriangleMesh& mesh,
                const MeshWriteOptions& options = {});

// Reads a triangle mesh from .ply (element "face" with a list property
// "vertex_indices" or "vertex_index"), .off or .obj ("f" with v, v/vt, v//vn or
// v/vt/vn corners; negative indices count from the end). Throws InputError
// with the same discipline as read_points, and also for faces that are not
// triangles, indices out of range, non-finite coordinates and files with no
// faces.
TriangleMesh read_mesh(const std::string& path);

// A named array of values, one per point or one per cell, for write_domain_vtu.
struct DataArray {
  std::string name;
  std::vector<double> values;
};

// Writes the domain as a VTK XML UnstructuredGrid (.vtu, ASCII) that ParaView
// opens: the points, the tetrahedra (VTK_TETRA), the point data "f" (one value
// per vertex) and any extra point or cell data. Throws std::invalid_argument
// when a size does not match, a tet refers to a missing vertex or a value is
// not finite (VTK's ASCII reader cannot read nan or inf), InputError when the
// extension is not .vtu or the target cannot be written. With `staged`, the
// file is renamed onto `path` by staged->commit() (MeshWriteOptions::staged).
void write_domain_vtu(const std::string& path, const TetMesh& mesh, const std::vector<double>& f,
                      const std::vector<DataArray>& point_data = {},
                      const std::vector<DataArray>& cell_data = {},
                      StagedOutputs* staged = nullptr);

// ------------------------------------------------------------ output paths

// What kind of file an output path names: a file, or a folder of files.
enum class OutputKind { kMesh, kPoints, kDomain, kStatistics, kFolder };

// Runs `write` on a stream into a new temporary file in path's folder, then
// renames the temporary to `path`. When `write` throws or any write, flush or
// rename fails, the temporary is removed, `path` is left as it was and the
// error is thrown on (InputError when the folder is missing or not writable,
// std::runtime_error for a failed write). Every writer above goes through it.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The outputs of one run, written together or not at all: add() writes each
// into a temporary next to its target at once (failing as write_atomically
// does) and commit() renames them all onto their targets. The temporaries not
// committed are removed when the object goes away, so a run that fails before
// commit() leaves every target as it was. Should a rename fail in commit()
// (the folder changed meanwhile), the outputs renamed before it are removed
// too and the error is thrown (std::runtime_error): none of them is left.
class StagedOutputs {
 public:
  StagedOutputs() = default;
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  ~StagedOutputs();
  void add(const std::string& path, const std::function<void(std::ostream&)>& write);
  // Creates `folder` (and its missing parents) for outputs to be staged in it;
  // unless committed, the folders it created are removed again when empty.
  void create_folder(const std::string& folder);
  void commit();
  // Removes the temporaries and the folders created so far, at once; safe to
  // call from another thread while add() runs (a watcher about to end the
  // process on a signal).
  void discard();

 private:
  std::mutex mutex_;
  struct Staged {
    std::string path;
    std::string temporary;
  };
  std::vector<Staged> staged_;
  std::vector<std::string> created_folders_;  // outermost first
};

// Checks, before any work is done, that `path` has an extension write_mesh
// (kMesh), write_points (kPoints) or write_domain_vtu (kDomain) accepts, or
// .json (kStatistics); that its folder exists and is writable; that no name
// in it is longer than the file system allows (NAME_MAX, PATH_MAX); that a
// file already there is a regular file (not a folder, a named pipe or a
// device); and that it is none of `inputs`, under another spelling or through
// a symbolic or hard link. kFolder (--save-iterations) names a folder that is
// created if missing: it must be a folder if it exists, and its nearest
// existing ancestor writable. Throws InputError naming the path otherwise.
void check_output_path(const std::string& path, OutputKind kind,
                       const std::vector<std::string>& inputs = {});

}  // namespace pdd
