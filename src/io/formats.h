// The per-format readers and writers behind pdd/io.h. Readers return what the
// file holds, with the line of every record for the messages of validation;
// writers stream into an std::ostream that write_atomically provides.
//
// The readers are written by hand rather than built on CGAL's (CGAL/IO/PLY.h,
// read_XYZ, read_OFF, read_OBJ): those report a failure as `false` plus, at
// best, a text on std::cerr, so they cannot name the line or the record at
// fault; they also accept some bad input silently (a missing normal becomes a
// null vector in read_XYZ, extra values on a line are ignored).
#pragma once

#include <pdd/io.h>

#include <array>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace pdd::io {

// The vertices a file holds, before validation.
struct RawVertices {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;       // empty, or one per point
  std::vector<Attribute> attributes;  // PLY: every other scalar vertex property
  std::vector<std::size_t> lines;  // line of each point in a text file; empty for binary files
  std::vector<std::string> remarks;  // what the reader left out, for read_points' warnings
};

// A mesh as a file holds it: faces are 0-based but not yet range-checked.
struct RawMesh {
  RawVertices vertices;
  std::vector<std::array<std::int64_t, 3>> faces;
  std::vector<std::size_t> face_lines;  // line of each face in a text file; empty for binary files
};

// Whether a reader reads the faces too or stops after the vertices.
enum class Content { kVertices, kVerticesAndFaces };

RawMesh read_ply(const std::string& path, const std::string& data, Content content);
RawMesh read_off(const std::string& path, const std::string& data, Content content);
// With Content::kVertices, "vn" normals are paired with "v" vertices in order
// and any other number of them than one per vertex is an error.
RawMesh read_obj(const std::string& path, const std::string& data, Content content);
RawVertices read_xyz(const std::string& path, const std::string& data);

// read_points and read_mesh on a file's content, `path` naming it (and its
// format, by its extension): what the fuzz targets (fuzz/) feed.
PointSet parse_points(const std::string& path, const std::string& data,
                      ValidationReport* report, const ValidationOptions& options);
TriangleMesh parse_mesh(const std::string& path, const std::string& data);

// validate_points with the line of each point (empty: number points instead).
PointSet validate_points_at(PointSet points, const std::string& source,
                            const std::vector<std::size_t>& lines, ValidationReport* report,
                            const ValidationOptions& options);

// Throws InputError naming `source` when an attribute has not one value per
// point, a duplicate name or an unknown type, or when the colours (red, green
// and blue together, optional alpha) are of another type than uchar, ushort,
// float or double, or out of their type's range (0-1 for floats). `lines`
// (the line of each point, or empty) names the point at fault.
void check_attributes(const std::string& source, const std::vector<Attribute>& attributes,
                      std::size_t n, const std::vector<std::size_t>& lines);

// Writers. `normals` is empty or one per vertex; `attributes` empty or each
// with one value per vertex; faces index `vertices` and
// are checked as they are written (std::invalid_argument when out of range).
using Faces = std::vector<std::array<int, 3>>;
void write_ply(std::ostream& out, const std::vector<Vec3>& vertices,
               const std::vector<Vec3>& normals, const std::vector<Attribute>& attributes,
               const Faces* faces, bool ascii);
// OFF and OBJ carry colours only (COFF with 0-255 values; OBJ's "v x y z r g b" with 0-1).
void write_off(std::ostream& out, const std::vector<Vec3>& vertices,
               const std::vector<Vec3>& normals, const std::vector<Attribute>& attributes,
               const Faces& faces);
void write_obj(std::ostream& out, const std::vector<Vec3>& vertices,
               const std::vector<Vec3>& normals, const std::vector<Attribute>& attributes,
               const Faces& faces);

// Whether a property of the PLY type `type` (a known one) holds `value`: a
// whole number in range for the integer types, within float's range for float.
bool type_holds(const std::string& type, double value);

// The colours of a text format's vertices (COFF, OBJ's "v x y z r g b"), one
// row of 3 or 4 values per vertex: the attributes red, green, blue [alpha],
// uchar when `integers` (0-255), else float (0-1, rounded to floats).
// check_attributes then checks their range.
std::vector<Attribute> colour_attributes(const std::vector<std::array<double, 4>>& rows,
                                         int channels, bool integers);

// The colour channels among `attributes` (red, green, blue, then alpha when
// there), or none when there are no colours.
std::vector<const Attribute*> colour_channels(const std::vector<Attribute>& attributes);
// Channel value `value` of `channel` on the scale 0-1.
double unit_colour(const Attribute& channel, double value);
void write_xyz(std::ostream& out, const std::vector<Vec3>& points,
               const std::vector<Vec3>& normals);

// write_atomically, or staged->add() when `staged` is set.
void write_output(const std::string& path, StagedOutputs* staged,
                  const std::function<void(std::ostream&)>& write);

// Throws std::invalid_argument when face `index` refers to a vertex outside
// [0, num_vertices).
void check_face(const std::array<int, 3>& face, std::size_t index, std::size_t num_vertices);

}  // namespace pdd::io
