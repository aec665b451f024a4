// The io stage: round trips through every format, every bad input named in
// issue 2 with the message it must produce, and atomic output.
#include <gtest/gtest.h>
#include <pdd/errors.h>
#include <pdd/io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>

#include <sys/stat.h>

#include "support/scratch_dir.h"
#include "support/shapes.h"

namespace pdd {
namespace {

namespace fs = std::filesystem;

class IoTest : public test::ScratchDirTest {};

// Runs f, expects an InputError whose message holds every fragment.
template <class F>
void expect_input_error(F f, std::initializer_list<std::string> fragments) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message: " << message << "\nmissing: " << fragment;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

void expect_same(const PointSet& a, const PointSet& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.normals.size(), b.normals.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i], b.points[i]) << "point " << i;
    if (a.has_normals()) {
      EXPECT_EQ(a.normals[i], b.normals[i]) << "normal " << i;
    }
  }
}

PointSet without_normals(PointSet p) {
  p.normals.clear();
  return p;
}

// Positions and normals rounded to float, as a float32 file holds them.
PointSet as_floats(const PointSet& p) {
  PointSet q = p;
  for (auto* v : {&q.points, &q.normals}) {
    for (Vec3& x : *v) x = x.cast<float>().cast<double>();
  }
  return q;
}

// A PLY written independently of pdd's writer, to test the reader.
struct PlyBuilder {
  bool ascii = false;
  bool big_endian = false;
  std::string header = "ply\n";
  std::string body;

  void begin(const char* format) { header += std::string("format ") + format + " 1.0\n"; }
  void line(const std::string& text) { header += text + "\n"; }
  template <class T>
  void put(T value) {
    if (ascii) {
      std::ostringstream s;
      s.precision(17);
      s << +value;
      if (!body.empty() && body.back() != '\n') body += ' ';
      body += s.str();
      return;
    }
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    const std::uint16_t one = 1;
    const bool host_little = *reinterpret_cast<const unsigned char*>(&one) == 1;
    if (host_little == big_endian) std::reverse(bytes, bytes + sizeof(T));
    body.append(reinterpret_cast<const char*>(bytes), sizeof(T));
  }
  void end_record() {
    if (ascii) body += '\n';
  }
  std::string text() const { return header + "end_header\n" + body; }
};

// Vertices with float or double x y z nx ny nz, an extra property before
// them and one after, and extra elements before and after the vertices.
template <class T>
std::string make_ply(const PointSet& p, const char* format, const char* type) {
  PlyBuilder b;
  b.ascii = std::string(format) == "ascii";
  b.big_endian = std::string(format) == "binary_big_endian";
  b.begin(format);
  b.line("comment made by io_test");
  b.line("obj_info something");
  b.line("element camera 1");
  b.line("property float focal");
  b.line("property list uchar int stuff");
  b.line("element vertex " + std::to_string(p.size()));
  b.line("property uchar red");
  for (const char* name : {"x", "y", "z", "nx", "ny", "nz"})
    b.line(std::string("property ") + type + " " + name);
  b.line("property list uint short extra");
  b.line("element face 1");
  b.line("property list uchar int vertex_indices");
  b.put(1.5f);
  b.put(std::uint8_t(2));
  b.put(std::int32_t(7));
  b.put(std::int32_t(-8));
  b.end_record();
  for (std::size_t i = 0; i < p.size(); ++i) {
    b.put(std::uint8_t(200));
    for (int k = 0; k < 3; ++k) b.put(static_cast<T>(p.points[i][k]));
    for (int k = 0; k < 3; ++k) b.put(static_cast<T>(p.normals[i][k]));
    b.put(std::uint32_t(i % 3));
    for (std::size_t k = 0; k < i % 3; ++k) b.put(std::int16_t(k));
    b.end_record();
  }
  b.put(std::uint8_t(3));
  for (int k = 0; k < 3; ++k) b.put(std::int32_t(k));
  b.end_record();
  return b.text();
}

const PointSet& sphere() {
  static const PointSet points = test::sample_sphere(60, 1.3, Vec3(0.1, -2.0, 1.0 / 3.0));
  return points;
}

// A tetrahedron, as a closed triangle mesh, with awkward coordinates.
TriangleMesh awkward_tetrahedron() {
  TriangleMesh m;
  m.vertices = {Vec3(0.1, 1.0 / 3.0, -0.0), Vec3(1e-300, std::nextafter(1.0, 2.0), 2.0 / 7.0),
                Vec3(-123456.789, 4.9e-324, 1e300), Vec3(std::sqrt(2.0), M_PI, -M_E)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

bool bitwise_equal(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

// ------------------------------------------------------------ round trips

TEST_F(IoTest, PointRoundTripsAreExactInEveryFormat) {
  const PointSet& p = sphere();
  for (const char* name :
       {"a.ply", "b.xyz", "c.pwn", "d.xyzn", "e.off", "f.obj", "G.PLY", "h.Xyz"}) {
    for (bool normals : {true, false}) {
      const PointSet source = normals ? p : without_normals(p);
      const std::string file = path(std::string(normals ? "n_" : "") + name);
      write_points(file, source);
      ValidationReport report;
      const PointSet back = read_points(file, &report);
      SCOPED_TRACE(file);
      expect_same(source, back);
      EXPECT_EQ(report.points_read, p.size());
      EXPECT_EQ(report.merged_duplicates, 0u);
      EXPECT_TRUE(report.warnings.empty());
    }
  }
  write_points(path("ascii.ply"), p, {true});
  expect_same(p, read_points(path("ascii.ply")));
  std::ifstream in(path("ascii.ply"));
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(second, "format ascii 1.0");
}

TEST_F(IoTest, ReadsPlyOfEveryEncodingWithFloatOrDoubleAndSkipsTheRest) {
  const PointSet& p = sphere();
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    SCOPED_TRACE(format);
    write_file("d.ply", make_ply<double>(p, format, "double"));
    expect_same(p, read_points(path("d.ply")));
    write_file("f.ply", make_ply<float>(p, format, "float32"));
    expect_same(as_floats(p), read_points(path("f.ply")));
  }
}

TEST_F(IoTest, ReadsPlyWithoutNormalsAndWithCrlfHeader) {
  std::string text =
      "ply\r\nformat ascii 1.0\r\nelement vertex 4\r\nproperty int x\r\n"
      "property int y\r\nproperty int z\r\nend_header\r\n"
      "0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n";
  const PointSet p = read_points(write_file("i.ply", text));
  ASSERT_EQ(p.size(), 4u);
  EXPECT_FALSE(p.has_normals());
  EXPECT_EQ(p.points[3], Vec3(0, 0, 1));
}

TEST_F(IoTest, ReadsTextFormatsWithCommentsAndVariants) {
  const PointSet xyz = read_points(write_file(
      "a.xyz",
      "# a comment\n4\n\n0 0 0 0 0 1\n+1 0 0 0 0 1  # trailing\n0 1 0 0 0 1\n0 0 1e0 0 0 1\n"));
  ASSERT_EQ(xyz.size(), 4u);
  EXPECT_EQ(xyz.points[1], Vec3(1, 0, 0));
  EXPECT_EQ(xyz.normals[3], Vec3(0, 0, 1));

  const PointSet coff = read_points(
      write_file("c.off",
                 "CNOFF 4 1 0\n0 0 0 0 0 1 255 0 0\n1 0 0 0 0 1 0 255 0\n0 1 0 0 0 1 1 1 1 1\n"
                 "0 0 1 0 0 2 0.5\n3 0 1 2\n"));
  ASSERT_EQ(coff.size(), 4u);
  EXPECT_EQ(coff.normals[3], Vec3(0, 0, 2));
  EXPECT_TRUE(coff.attributes.empty());  // 3, 3, 4 and 1 colour values: not read, and said
  ValidationReport report;
  read_points(path("c.off"), &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("line 4: vertex 3 has 4 colour values, the first vertex 3"),
            std::string::npos)
      << report.warnings[0];

  const PointSet obj = read_points(
      write_file("o.obj",
                 "mtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1\nv 0 1 0 0.5 0.5 0.5\nv 0 0 1\n"
                 "vt 0 0\nvn 1 0 0\nvn 0 1 0\nvn 0 0 1\nvn 1 1 1\nf 1//1 2//2 3//3\n"));
  ASSERT_EQ(obj.size(), 4u);
  EXPECT_EQ(obj.points[2], Vec3(0, 1, 0));
  EXPECT_EQ(obj.normals[3], Vec3(1, 1, 1));
}

TEST_F(IoTest, MeshRoundTripsInEveryFormat) {
  const TriangleMesh m = awkward_tetrahedron();
  for (const char* name : {"m.ply", "m.off", "m.obj", "M.OBJ"}) {
    for (bool ascii : {false, true}) {
      SCOPED_TRACE(std::string(name) + (ascii ? " ascii" : ""));
      write_mesh(path(name), m, {ascii});
      const TriangleMesh back = read_mesh(path(name));
      ASSERT_EQ(back.vertices.size(), m.vertices.size());
      for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        EXPECT_TRUE(bitwise_equal(back.vertices[i], m.vertices[i])) << i;
      }
      EXPECT_EQ(back.faces, m.faces);
    }
  }
}

TEST_F(IoTest, BinaryPlyOfTheToolHoldsPositionsBitForBit) {
  // Many random doubles over many magnitudes, written and read back.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-300, 300);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  TriangleMesh m;
  for (int i = 0; i < 3000; ++i) {
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = mantissa(rng) * std::pow(10.0, exponent(rng));
    m.vertices.push_back(v);
  }
  for (int i = 0; i + 2 < 3000; i += 3) m.faces.push_back({i, i + 1, i + 2});
  write_mesh(path("r.ply"), m);
  const TriangleMesh back = read_mesh(path("r.ply"));
  ASSERT_EQ(back.vertices.size(), m.vertices.size());
  EXPECT_EQ(std::memcmp(back.vertices.data(), m.vertices.data(), sizeof(Vec3) * m.vertices.size()),
            0);
  EXPECT_EQ(back.faces, m.faces);
  // Header, then 24 bytes per vertex and 1 + 12 per face: binary by default.
  const std::string header_end = "end_header\n";
  std::ifstream in(path("r.ply"), std::ios::binary);
  const std::string content((std::istreambuf_iterator<char>(in)), {});
  const std::size_t body = content.find(header_end) + header_end.size();
  EXPECT_NE(content.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_EQ(content.size() - body, 24 * m.vertices.size() + 13 * m.faces.size());
  // ASCII text reads back identically too.
  write_mesh(path("r_ascii.ply"), m, {true});
  const TriangleMesh text = read_mesh(path("r_ascii.ply"));
  EXPECT_EQ(std::memcmp(text.vertices.data(), m.vertices.data(), sizeof(Vec3) * m.vertices.size()),
            0);
}

TEST_F(IoTest, ReadsMeshVariants) {
  const TriangleMesh obj = read_mesh(
      write_file("v.obj",
                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf -3 -1 -2\n"
                 "v 0 0 1\nf 1//1 4//1 2//1\n"));
  ASSERT_EQ(obj.faces.size(), 3u);
  EXPECT_EQ(obj.faces[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(obj.faces[1], (std::array<int, 3>{0, 2, 1}));
  EXPECT_EQ(obj.faces[2], (std::array<int, 3>{0, 3, 1}));

  const TriangleMesh off = read_mesh(write_file(
      "c.off", "# comment\nCOFF\n3 1 3\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2 255 0 0\n"));
  EXPECT_EQ(off.faces.size(), 1u);

  PlyBuilder b;
  b.begin("binary_big_endian");
  b.line("element vertex 3");
  for (const char* c : {"x", "y", "z"}) b.line(std::string("property float ") + c);
  b.line("element face 1");
  b.line("property uchar flags");
  b.line("property list uint8 uint32 vertex_index");
  b.big_endian = true;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.put(v);
  b.put(std::uint8_t(9));
  b.put(std::uint8_t(3));
  for (std::uint32_t i : {2u, 1u, 0u}) b.put(i);
  const TriangleMesh ply = read_mesh(write_file("b.ply", b.text()));
  EXPECT_EQ(ply.vertices[1], Vec3(1, 0, 0));
  EXPECT_EQ(ply.faces[0], (std::array<int, 3>{2, 1, 0}));
}

// ------------------------------------------------------------ bad input

TEST_F(IoTest, MissingUnreadableOrUnknownFiles) {
  expect_input_error([&] { read_points(path("none.ply")); }, {path("none.ply"), "no such file"});
  fs::create_directory(path("folder.xyz"));
  expect_input_error([&] { read_points(path("folder.xyz")); }, {path("folder.xyz"), "is a folder"});
  write_file("p.stl", "solid\n");
  expect_input_error([&] { read_points(path("p.stl")); },
                     {path("p.stl"), "unknown extension '.stl'", ".ply", ".xyz", ".obj"});
  expect_input_error([&] { read_points(path("noext")); }, {path("noext"), "no file extension"});
  expect_input_error([&] { read_mesh(path("m.xyz")); },
                     {path("m.xyz"), "unknown extension '.xyz' for a mesh"});
}

TEST_F(IoTest, MalformedPlyHeaders) {
  const std::string tail =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
  struct Case {
    std::string text;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"plx\nformat ascii 1.0\n" + tail + "end_header\n", {"not a PLY file"}},
      {"ply\n" + tail + "end_header\n", {"malformed header", "no 'format' line"}},
      {"ply\nformat text 1.0\n" + tail + "end_header\n", {"line 2", "unknown format 'text'"}},
      {"ply\nformat ascii 1.0\n" + tail, {"malformed header", "no 'end_header'"}},
      {"ply\nformat ascii 1.0\nelement vertex 4\nproperty float16 x\nend_header\n",
       {"line 4", "unknown property type 'float16'"}},
      {"ply\nformat ascii 1.0\nelement vertex four\nend_header\n",
       {"line 3", "expected 'element <name> <count>'"}},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", {"line 3", "before any 'element'"}},
      {"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nend_header\n",
       {"element 'vertex' has no property 'z'"}},
      {"ply\nformat ascii 1.0\n" + tail + "property float nx\nend_header\n",
       {"some of nx, ny, nz"}},
      {"ply\nformat ascii 1.0\nelement face 0\nend_header\n", {"no element 'vertex'"}},
      {"ply\nformat binary_little_endian 1.0\n" + tail + std::string("\x01\x02\x03\x04", 4),
       {"no 'end_header'"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string file = write_file("h.ply", c.text);
    try {
      read_points(file);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(file + ": ", 0), 0u) << e.what();
      for (const std::string& f : c.fragments) {
        EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what() << " / " << f;
      }
    }
  }
}

TEST_F(IoTest, TruncatedOrOverlongPlyBodies) {
  const PointSet& p = sphere();
  const std::string binary = make_ply<float>(p, "binary_little_endian", "float");
  // Cut inside vertex 11: camera record (4 + 1 + 8 bytes) and ten vertices before it.
  std::size_t offset = binary.find("end_header\n") + 11 + 13;
  for (int i = 0; i < 10; ++i) offset += 1 + 24 + 4 + 2 * (i % 3);
  write_file("t.ply", binary.substr(0, offset + 5));
  expect_input_error([&] { read_points(path("t.ply")); },
                     {path("t.ply"), "truncated", "60 'vertex' records of at least 29 bytes"});
  // Enough bytes for 60 records without their lists, not with them: found while reading.
  write_file("t.ply", binary.substr(0, binary.size() - 13 - 60));
  expect_input_error([&] { read_points(path("t.ply")); },
                     {path("t.ply"), "truncated", "'vertex' record 59 of the 60"});
  write_file("t.ply", binary + "xy");
  expect_input_error([&] { read_points(path("t.ply")); },
                     {"2 bytes of data after the last element"});

  const std::string ascii = make_ply<float>(p, "ascii", "float");
  // The header, the camera and two vertices.
  std::size_t cut = ascii.find("end_header\n") + 11;
  for (int i = 0; i < 3; ++i) cut = ascii.find('\n', cut) + 1;
  write_file("a.ply", ascii.substr(0, cut));
  expect_input_error([&] { read_points(path("a.ply")); },
                     {"truncated", "after 2 of the 60 'vertex' records"});
  write_file("a.ply", ascii + "\n4 5 6\n");
  const auto lines = std::count(ascii.begin(), ascii.end(), '\n');
  expect_input_error([&] { read_points(path("a.ply")); },
                     {"line " + std::to_string(lines + 2), "data after the last element"});
}

TEST_F(IoTest, PlyLinesThatDoNotParseAreNamed) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  write_file("a.ply", head + "0 0 0\n1 0 0\n0 1 zero\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.ply")); },
                     {path("a.ply"), "line 10", "'zero' is not a number"});
  write_file("a.ply", head + "0 0 0\n1 0\n0 1 0\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.ply")); },
                     {"line 9", "'vertex' record 2 has too few values"});
  write_file("a.ply", head + "0 0 0\n1 0 0 7\n0 1 0\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.ply")); }, {"line 9", "1 more values"});
  // A text value its property's type cannot hold (found by fuzz/ply_fuzzer.cpp: the
  // 256 was written back into a uchar).
  const std::string typed =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar label\n"
      "property short s\nproperty float f\nend_header\n";
  for (const auto& [values, message] : std::vector<std::pair<std::string, std::string>>{
           {"256 0 0", "'label' is a uchar, which cannot hold '256'"},
           {"-1 0 0", "'label' is a uchar, which cannot hold '-1'"},
           {"2.5 0 0", "'label' is a uchar, which cannot hold '2.5'"},
           {"1 40000 0", "'s' is a short, which cannot hold '40000'"},
           {"1 0 1e39", "'f' is a float, which cannot hold '1e39'"}}) {
    write_file("a.ply", typed + "0 0 0 1 0 0\n1 0 0 " + values + "\n0 1 0 1 0 0\n0 0 1 1 0 0\n");
    expect_input_error([&] { read_points(path("a.ply")); }, {path("a.ply"), "line 12", message});
  }
  // Lists too: their counts and items (found by fuzz/ply_fuzzer.cpp: an index of 1.4e113
  // in an int list was cast to an integer, undefined behaviour).
  const std::string faces =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  for (const auto& [face, message] : std::vector<std::pair<std::string, std::string>>{
           {"3 0 1 144444444444444444444444", "are ints, which cannot hold '144444444444444444444444'"},
           {"3 0 1 2.5", "are ints, which cannot hold '2.5'"},
           {"300 0 1 2", "is a uchar, which cannot hold '300'"}}) {
    write_file("f.ply", faces + face + "\n");
    expect_input_error([&] { read_mesh(path("f.ply")); }, {path("f.ply"), "line 13", message});
  }
  std::string floats = faces;
  floats.replace(floats.find("uchar int"), 9, "uchar float");
  write_file("f.ply", floats + "3 0 1 1e30\n");
  expect_input_error([&] { read_mesh(path("f.ply")); },
                     {path("f.ply"), "face 1 refers to vertex 1e+30, which cannot exist"});
  // A text float is read as the float it declares, so that it is written back the same.
  write_file("a.ply", typed + "0 0 0 1 0 0.1\n1 0 0 1 0 0\n0 1 0 1 0 0\n0 0 1 1 0 0\n");
  EXPECT_EQ(read_points(path("a.ply")).attributes[2].values[0], static_cast<double>(0.1f));
}

TEST_F(IoTest, TextLinesThatDoNotParseAreNamed) {
  write_file("a.xyz", "0 0 0\n1 0 0\n\n# c\n0 1 O\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {path("a.xyz"), "line 5", "'O' is not a number"});
  write_file("a.xyz", "\n0 0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {"line 2", "expected 3 values (x y z) or 6 (x y z nx ny nz), found 4"});
  write_file("a.xyz", "0 0 0\n1 0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {"line 2", "found 4 values, but line 1 has 3"});
  write_file("a.xyz", "0 0 0 0 0 1\n1 0 0\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {"line 2", "found 3 values, but line 1 has 6"});
  write_file("a.xyz", "5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {"line 1", "announces 5 points, but the file has 4"});

  write_file("a.off", "OFF\n4 0 0\n0 0 0\n1 0 0\n0 1\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.off")); },
                     {path("a.off"), "line 5", "vertex 3 has 2 values, expected x y z"});
  write_file("a.off", "NOFF\n4 0 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n");
  expect_input_error([&] { read_points(path("a.off")); },
                     {"truncated", "after 2 of the 4 vertices"});
  write_file("a.off", "PLY\n4 0 0\n");
  expect_input_error([&] { read_points(path("a.off")); }, {"not an OFF file"});
  write_file("a.off", "OFF\n4 zero 0\n");
  expect_input_error([&] { read_points(path("a.off")); }, {"line 2", "malformed header"});

  write_file("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1\nv 0 0 1\n");
  expect_input_error([&] { read_points(path("a.obj")); },
                     {path("a.obj"), "line 3", "'v' has 2 values"});
  write_file("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n");
  expect_input_error([&] { read_points(path("a.obj")); }, {"1 normals (vn) for 4 vertices (v)"});
  write_file("a.obj", "v 0 0 0 2\n");
  expect_input_error([&] { read_points(path("a.obj")); }, {"line 1", "weight w = '2'"});
}

TEST_F(IoTest, TokensInMessagesAreEscapedAndShortened) {
  // A NUL, a terminal escape sequence and a long token, quoted as they go
  // into a message: every byte printable, the line short.
  const std::string nul("0 0 z\0ero\n", 11);
  const std::string escape = "0 0 \x1b[31mred\n";
  const std::string longer = "0 0 " + std::string(1 << 20, '7') + "x\n";
  for (const auto& [text, shown] :
       {std::pair(nul, "'z\\x00ero'"), std::pair(escape, "'\\x1b[31mred'"),
        std::pair(longer, "'7777777777777777777777777777777777777777...'")}) {
    write_file("a.xyz", text);
    try {
      read_points(path("a.xyz"));
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(std::string("line 1: ") + shown + " is not a number"),
                std::string::npos)
          << message;
      EXPECT_LT(message.size(), path("a.xyz").size() + 100) << message;
      for (const char c : message) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << int(c);
    }
  }
  // Names from a PLY header too.
  write_file("h.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                      "property float y\nproperty float z\nelement " + std::string(5000, 'n') +
                          " 5\nproperty float w\nend_header\n");
  expect_input_error([&] { read_points(path("h.ply")); }, {"5 'nnnnnnnnnn", "...' records"});
  try {
    read_points(path("h.ply"));
  } catch (const InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), path("h.ply").size() + 200) << e.what();
  }
}

TEST_F(IoTest, CountsTheFileCannotHoldFailBeforeAnyRecordIsRead) {
  const std::string vertices =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string body(4 * 12, '\0');
  // Records without properties take no bytes: any count of them is refused.
  write_file("j.ply", "ply\nformat binary_little_endian 1.0\n" + vertices +
                          "element junk 9000000000000000000\nend_header\n" + body);
  expect_input_error([&] { read_points(path("j.ply")); },
                     {path("j.ply"), "line 7", "element 'junk' declares 9000000000000000000 "
                                               "records but no properties"});
  expect_input_error([&] { read_mesh(path("j.ply")); }, {path("j.ply"), "'junk'"});
  // None of them is fine (found by fuzz/ply_fuzzer.cpp: the count check divided by their size, 0).
  std::string tetrahedron;
  for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f})
    tetrahedron.append(reinterpret_cast<const char*>(&v), sizeof v);
  write_file("z.ply", "ply\nformat binary_little_endian 1.0\n" + vertices +
                          "element empty 0\nend_header\n" + tetrahedron);
  EXPECT_EQ(read_points(path("z.ply")).size(), 4u);
  // Records of a byte or more: the count against the bytes after the header.
  write_file("k.ply", "ply\nformat binary_big_endian 1.0\n" + vertices +
                          "element junk 9000000000000000000\nproperty list uchar int stuff\n"
                          "end_header\n" + body + "\x01\x02");
  expect_input_error([&] { read_points(path("k.ply")); },
                     {path("k.ply"), "line 7", "9000000000000000000 'junk' records of at least 1 "
                                               "byte each, but only 2 bytes are left"});
  write_file("v.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n" + body);
  expect_input_error([&] { read_points(path("v.ply")); },
                     {"line 3", "5 'vertex' records of at least 12 bytes each, but only 48"});
  // ASCII: a record is a line of at least one byte.
  write_file("a.ply", "ply\nformat ascii 1.0\nelement vertex 9000000000000000000\n"
                      "property float x\nproperty float y\nproperty float z\nend_header\n"
                      "0 0 0\n1 0 0\n");
  expect_input_error([&] { read_points(path("a.ply")); },
                     {"line 3", "9000000000000000000 'vertex' records of at least 1 byte (a line)"});
  write_file("f.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 4611686018427387904\n"
                      "property list uchar int vertex_indices\nend_header\n"
                      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_input_error([&] { read_mesh(path("f.ply")); }, {"line 7", "'face' records"});
  // OFF: one line per vertex and per face.
  write_file("a.off", "OFF\n9000000000000000000 1 0\n0 0 0\n");
  expect_input_error([&] { read_points(path("a.off")); },
                     {path("a.off"), "line 2", "declares 9000000000000000000 vertices and 1 faces"});
  write_file("b.off", "OFF\n3 9000000000000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_input_error([&] { read_mesh(path("b.off")); }, {"line 2", "9000000000000000000 faces"});
}

TEST_F(IoTest, NonFiniteCoordinatesAreNamed) {
  write_file("a.xyz", "0 0 0\n1 0 0\n# skip\n0 nan 0\n0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {path("a.xyz"), "line 4 (point 3)", "(0, nan, 0) is not finite"});
  write_file("a.xyz", "0 0 0 0 0 1\n1 0 0 0 0 inf\n0 1 0 0 0 1\n0 0 1 0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {"line 2 (point 2)", "the normal (0, 0, inf) is not finite"});
  PointSet p = sphere();
  p.points[4].x() = std::numeric_limits<double>::infinity();
  write_points(path("b.ply"), p);
  expect_input_error([&] { read_points(path("b.ply")); }, {path("b.ply"), "point 5", "(inf, "});
}

TEST_F(IoTest, ZeroNormalsAreMissingOnesCountedAndKept) {
  write_file("a.xyz", "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 0\n0 0 1 0 0 1\n");
  ValidationReport report;
  const PointSet p = read_points(path("a.xyz"), &report);
  EXPECT_EQ(p.normals[2], Vec3::Zero());
  EXPECT_EQ(report.zero_normals, 1u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find(path("a.xyz") + ": 1 point has a zero normal (the first: "
                                    "line 3 (point 3))"),
            std::string::npos)
      << report.warnings[0];
  write_file("a.xyz", "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 nan 0\n0 0 1 0 0 1\n");
  expect_input_error([&] { read_points(path("a.xyz")); }, {"line 3 (point 3)", "not finite"});
}

TEST_F(IoTest, TooFewPoints) {
  write_file("a.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {path("a.xyz"), "only 3 points; at least 4 are needed"});
  write_file("b.xyz", "# nothing\n");
  expect_input_error([&] { read_points(path("b.xyz")); }, {path("b.xyz"), "holds no points"});
  write_file("c.xyz", "0 0 0\n1 0 0\n0 1 0\n1 0 0\n0 0 0\n");
  expect_input_error([&] { read_points(path("c.xyz")); }, {"only 3 distinct points (of 5)"});
}

TEST_F(IoTest, CoincidentPoints) {
  write_file("a.xyz", "1 2 3\n1 2 3\n1 2 3\n1 2 3\n1 2 3\n");
  expect_input_error([&] { read_points(path("a.xyz")); },
                     {path("a.xyz"), "all 5 points are at the same position (1, 2, 3)"});
  // Distinct, but only in the last bits of large coordinates.
  PointSet p;
  for (int i = 0; i < 8; ++i) p.points.push_back(Vec3(1e6 + i * 1e-7, 1e6, 1e6 - i * 1e-7));
  expect_input_error([&] { validate_points(p, "mem"); }, {"mem: all 8 points coincide"});
}

TEST_F(IoTest, CoplanarOrCollinearPoints) {
  // A tilted plane through random points: not aligned with any axis.
  const Vec3 u = Vec3(1, 2, 3).normalized();
  const Vec3 v = u.cross(Vec3(0, 0, 1)).normalized();
  const Vec3 w = u.cross(v);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(-5, 5);
  PointSet plane;
  PointSet line;
  for (int i = 0; i < 200; ++i) {
    plane.points.push_back(Vec3(10, 20, 30) + r(rng) * v + r(rng) * w);
    line.points.push_back(Vec3(10, 20, 30) + r(rng) * u);
  }
  write_points(path("plane.xyz"), plane);
  expect_input_error([&] { read_points(path("plane.xyz")); },
                     {path("plane.xyz"), "all 200 points lie in one plane"});
  expect_input_error([&] { validate_points(line, "line.xyz"); },
                     {"line.xyz: all 200 points lie on one line"});
  // Lifting one point by 1e-3 (1e-4 of the diagonal) makes the set valid.
  plane.points[17] += 1e-3 * u;
  EXPECT_EQ(validate_points(plane, "lifted").size(), 200u);
}

TEST_F(IoTest, FarFromTheOriginIsJudgedOnTheOwnExtent) {
  // The kitten scan in UTM-like coordinates: valid as it is at the origin.
  const PointSet kitten = read_points(std::string(PDD_SOURCE_DIR) + "/data/kitten_scan.ply");
  PointSet shifted = kitten;
  for (Vec3& p : shifted.points) p += Vec3(5e6, 5e6, 0);
  EXPECT_EQ(validate_points(shifted, "shifted").size(), kitten.size());
  for (Vec3& p : shifted.points) p += Vec3(1e9, -3e9, 1e8);
  EXPECT_EQ(validate_points(shifted, "far").size(), kitten.size());
  // A tilted plane far away is still a plane.
  PointSet plane;
  for (int i = 0; i < 50; ++i)
    plane.points.push_back(Vec3(5e6, 5e6, 100) + Vec3(i % 7, i / 7, 0.5 * (i % 7) + 0.25 * (i / 7)));
  expect_input_error([&] { validate_points(plane, "p"); }, {"p: all 50 points lie in one plane"});
}

TEST_F(IoTest, ExtentsOutOfRangeAndOutliersAreNamed) {
  const PointSet huge = test::sample_sphere(200, 1e300);
  expect_input_error([&] { validate_points(huge, "huge"); },
                     {"huge: all 200 points span 3.45e+300", "more than the 1e+50"});
  const PointSet tiny = test::sample_sphere(200, 1e-60);
  expect_input_error([&] { validate_points(tiny, "tiny"); },
                     {"tiny: all 200 points span only", "less than the 1e-50"});
  // One point far away makes the rest look like a line: it is named instead.
  PointSet outlier = test::sample_sphere(200);
  outlier.points.push_back(Vec3(1e15, 0, 0));
  outlier.normals.push_back(Vec3(1, 0, 0));
  write_points(path("o.xyz"), outlier);
  expect_input_error([&] { read_points(path("o.xyz")); },
                     {path("o.xyz") + ": line 201 (point 201) at (1e+15, 0, 0) is an "
                                      "outlier: the other 200 points span 3.45, all 201 span 1e+15"});
  outlier.points.push_back(Vec3(0, -1e14, 0));
  outlier.normals.push_back(Vec3(1, 0, 0));
  expect_input_error([&] { validate_points(outlier, "two"); },
                     {"two: 2 points are outliers, the farthest point 201", "remove them"});
  // So is one whose distance overflows the extent.
  outlier.points.back() = Vec3(0, 0, -1.7e308);
  expect_input_error([&] { validate_points(outlier, "inf"); },
                     {"inf: 2 points are outliers, the farthest point 202 at (0, 0, -1.7e+308)"});
}

TEST_F(IoTest, NormalsRequiredButAbsent) {
  const PointSet p = without_normals(sphere());
  write_points(path("p.xyz"), p);
  const PointSet back = read_points(path("p.xyz"));
  expect_input_error(
      [&] { require_normals(back, path("p.xyz"), "the SSD solver needs oriented normals"); },
      {path("p.xyz"), "no normals", "the SSD solver needs oriented normals"});
  EXPECT_NO_THROW(require_normals(sphere(), "s", "why"));
}

TEST_F(IoTest, DuplicatesAreMergedAndCounted) {
  PointSet p = sphere();
  PointSet with = p;
  with.points.push_back(p.points[3]);
  with.normals.push_back(p.normals[3]);
  with.points.push_back(p.points[3]);
  with.normals.push_back(-p.normals[3]);  // same position, another normal
  with.points.insert(with.points.begin(), p.points[40]);
  with.normals.insert(with.normals.begin(), p.normals[40]);
  write_points(path("d.ply"), with);
  ValidationReport report;
  const PointSet merged = read_points(path("d.ply"), &report);
  EXPECT_EQ(report.points_read, p.size() + 3);
  EXPECT_EQ(report.merged_duplicates, 3u);
  EXPECT_EQ(report.merged_with_other_normal, 1u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find(path("d.ply") + ": merged 3 duplicate points"),
            std::string::npos)
      << report.warnings[0];
  EXPECT_NE(report.warnings[0].find(std::to_string(p.size()) + " points remain"),
            std::string::npos);
  // The first occurrence of each position stays, in order.
  ASSERT_EQ(merged.size(), p.size());
  EXPECT_EQ(merged.points[0], p.points[40]);
  for (std::size_t i = 0, j = 1; i < p.size(); ++i) {
    if (i == 40) continue;
    EXPECT_EQ(merged.points[j], p.points[i]);
    EXPECT_EQ(merged.normals[j], p.normals[i]);
    ++j;
  }
}

TEST_F(IoTest, BadMeshFiles) {
  write_file("q.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  expect_input_error([&] { read_mesh(path("q.off")); },
                     {path("q.off"), "line 7", "face 1 has 4 vertices; only triangle"});
  write_file("r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n");
  expect_input_error([&] { read_mesh(path("r.off")); },
                     {"line 6", "face 1 refers to vertex 3, but the file has 3 vertices"});
  write_file("r.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expect_input_error([&] { read_mesh(path("r.obj")); },
                     {"line 4", "refers to vertex 4, but the file has 3"});
  write_file("s.obj", "v 0 0 0\nf 1 -2 1\n");
  expect_input_error([&] { read_mesh(path("s.obj")); },
                     {"line 2", "vertex -2 is before the first vertex"});
  write_file("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
  expect_input_error([&] { read_mesh(path("t.obj")); }, {"line 4", "'0' is not a face corner"});
  write_file("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_input_error([&] { read_mesh(path("n.obj")); }, {path("n.obj"), "holds no faces"});
  write_file("n.ply",
             "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
             "property float z\nend_header\n");
  expect_input_error([&] { read_mesh(path("n.ply")); }, {"no element 'face'"});
  write_file("q.ply",
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
             "end_header\n0 0 0\n4 0 0 0 0\n");
  expect_input_error([&] { read_mesh(path("q.ply")); }, {"line 11", "face 1 has 4 vertices"});
  write_file("i.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n1 1 0\n3 0 1 2\n");
  expect_input_error([&] { read_mesh(path("i.off")); },
                     {"line 4", "vertex 2 has a coordinate that is not finite"});
}

// ------------------------------------------------------------ atomic output

TEST_F(IoTest, WriterFailuresLeaveNoFile) {
  const TriangleMesh m = awkward_tetrahedron();
  // A folder that does not exist, or a file where a folder should be.
  expect_input_error(
      [&] { write_mesh(path("missing/m.ply"), m); },
      {path("missing/m.ply"), "the folder '" + path("missing") + "' does not exist"});
  write_file("plain", "x");
  expect_input_error([&] { write_mesh(path("plain/m.ply"), m); },
                     {path("plain/m.ply"), "is not a folder"});
  expect_input_error([&] { write_mesh(path("m.stl"), m); },
                     {path("m.stl"), "unknown extension '.stl' for a mesh"});
  fs::create_directory(path("d.ply"));
  expect_input_error([&] { write_mesh(path("d.ply"), m); }, {path("d.ply"), "it is a folder"});
  fs::remove(path("d.ply"));
  fs::remove(path("plain"));
  EXPECT_TRUE(entries().empty());

  // A face that refers to a missing vertex fails in the middle of writing.
  TriangleMesh bad = m;
  bad.faces.push_back({0, 1, 4});
  for (const char* name : {"b.ply", "b.off", "b.obj"}) {
    EXPECT_THROW(write_mesh(path(name), bad), std::invalid_argument) << name;
  }
  EXPECT_TRUE(entries().empty());

  // A failure never touches an existing file.
  write_mesh(path("keep.ply"), m);
  const auto size = fs::file_size(path("keep.ply"));
  EXPECT_THROW(write_mesh(path("keep.ply"), bad), std::invalid_argument);
  EXPECT_EQ(fs::file_size(path("keep.ply")), size);
  EXPECT_THROW(write_atomically(path("keep.ply"),
                                [](std::ostream& out) {
                                  out << std::string(100000, 'x');
                                  throw std::runtime_error("stop");
                                }),
               std::runtime_error);
  EXPECT_EQ(entries(), std::vector<std::string>{"keep.ply"});
  EXPECT_EQ(read_mesh(path("keep.ply")).faces, m.faces);
}

TEST_F(IoTest, AtomicWriteReplacesTheTarget) {
  write_file("a.txt", "old content that is longer");
  write_atomically(path("a.txt"), [](std::ostream& out) { out << "new"; });
  std::ifstream in(path("a.txt"));
  std::string content((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(content, "new");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.txt"});
}

TEST_F(IoTest, CheckOutputPath) {
  EXPECT_NO_THROW(check_output_path(path("m.PLY"), OutputKind::kMesh));
  EXPECT_NO_THROW(check_output_path(path("p.xyz"), OutputKind::kPoints));
  EXPECT_NO_THROW(check_output_path(path("d.vtu"), OutputKind::kDomain));
  expect_input_error([&] { check_output_path(path("m.xyz"), OutputKind::kMesh); },
                     {"unknown extension '.xyz' for a mesh"});
  expect_input_error([&] { check_output_path(path("d.ply"), OutputKind::kDomain); },
                     {"expected one of .vtu"});
  expect_input_error([&] { check_output_path(path("no/m.ply"), OutputKind::kMesh); },
                     {path("no/m.ply"), "does not exist"});
  EXPECT_TRUE(entries().empty());
}

TEST_F(IoTest, CheckOutputPathRefusesLongNamesSpecialFilesAndTheInput) {
  const std::string long_name = path(std::string(300, 'm') + ".ply");
  expect_input_error([&] { check_output_path(long_name, OutputKind::kMesh); },
                     {long_name, "a name in it is 304 bytes long, more than the 255"});
  std::string deep = path("");
  while (deep.size() < 5000) deep += std::string(200, 'd') + "/";
  expect_input_error([&] { check_output_path(deep + "m.ply", OutputKind::kMesh); },
                     {"the path is", "bytes long, more than the 4095"});
  ASSERT_EQ(::mkfifo(path("pipe.ply").c_str(), 0600), 0);
  expect_input_error([&] { check_output_path(path("pipe.ply"), OutputKind::kMesh); },
                     {path("pipe.ply"), "it is a named pipe, not a regular file"});

  // The input under another spelling, through a symbolic or a hard link.
  write_points(path("in.ply"), sphere());
  fs::create_directory(path("sub"));
  fs::create_symlink(path("in.ply"), path("soft.ply"));
  fs::create_hard_link(path("in.ply"), path("hard.ply"));
  fs::create_symlink(path("in.ply"), path("stats.json"));
  for (const std::string& alias :
       {path("in.ply"), path("sub/../in.ply"), path("./in.ply"), path("soft.ply"), path("hard.ply")})
    expect_input_error([&] { check_output_path(alias, OutputKind::kMesh, {path("in.ply")}); },
                       {alias + ": cannot write: it is the input file " + path("in.ply")});
  expect_input_error(
      [&] { check_output_path(path("stats.json"), OutputKind::kStatistics, {path("in.ply")}); },
      {"it is the input file"});
  EXPECT_NO_THROW(check_output_path(path("out.ply"), OutputKind::kMesh, {path("in.ply")}));
  EXPECT_NO_THROW(check_output_path(path("in.ply"), OutputKind::kMesh, {path("other.ply")}));

  // A folder of outputs: created if missing, so its nearest existing ancestor counts.
  EXPECT_NO_THROW(check_output_path(path("new/deeper"), OutputKind::kFolder));
  EXPECT_NO_THROW(check_output_path(path("sub"), OutputKind::kFolder));
  expect_input_error([&] { check_output_path(path("in.ply"), OutputKind::kFolder); },
                     {path("in.ply"), "it is a regular file, not a folder"});
  expect_input_error([&] { check_output_path(path("in.ply/x"), OutputKind::kFolder); },
                     {path("in.ply/x"), "Not a directory"});
  expect_input_error(
      [&] { check_output_path(path(std::string(300, 'f')), OutputKind::kFolder); },
      {"a name in it is 300 bytes long"});
  EXPECT_FALSE(fs::exists(path("new")));
}

TEST_F(IoTest, StagedOutputsAreRenamedTogetherOrNotAtAll) {
  write_file("old.json", "old");
  const auto text = [](const char* s) { return [s](std::ostream& out) { out << s; }; };
  {
    // A failed write: the outputs staged before it go too, the targets stay as they were.
    StagedOutputs outputs;
    outputs.add(path("a.txt"), text("a"));
    EXPECT_THROW(outputs.add(path("old.json"),
                             [](std::ostream& out) {
                               out << "half";
                               throw std::runtime_error("stop");
                             }),
                 std::runtime_error);
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"old.json"});
  EXPECT_EQ(slurp(path("old.json")), "old");
  {
    // Nothing is visible before commit(), everything after.
    StagedOutputs outputs;
    outputs.add(path("a.txt"), text("a"));
    outputs.add(path("old.json"), text("new"));
    EXPECT_EQ(slurp(path("old.json")), "old");
    EXPECT_FALSE(fs::exists(path("a.txt")));
    outputs.commit();
  }
  EXPECT_EQ(slurp(path("a.txt")), "a");
  EXPECT_EQ(slurp(path("old.json")), "new");
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.txt", "old.json"}));
  {
    // A rename that fails at commit() (the target became a folder): none is left.
    StagedOutputs outputs;
    outputs.add(path("b.txt"), text("b"));
    outputs.add(path("c.txt"), text("c"));
    outputs.add(path("d.txt"), text("d"));
    fs::create_directory(path("c.txt"));
    write_file("c.txt/keep", "x");
    EXPECT_THROW(outputs.commit(), std::runtime_error);
  }
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.txt", "c.txt", "old.json"}));
  // Writers stage when asked.
  {
    StagedOutputs outputs;
    write_mesh(path("m.ply"), awkward_tetrahedron(), {false, &outputs});
    write_domain_vtu(path("d.vtu"), {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                                     {{0, 1, 2, 3}}},
                     {0, 1, 2, 3}, {}, {}, &outputs);
    EXPECT_FALSE(fs::exists(path("m.ply")));
    EXPECT_FALSE(fs::exists(path("d.vtu")));
  }
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.txt", "c.txt", "old.json"}));
}

// ------------------------------------------------------------ domain output

TEST_F(IoTest, WritesTheDomainAsVtu) {
  TetMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  const std::vector<double> f = {-1, 0.5, 1.0 / 3.0, 2, 1e-300};
  write_domain_vtu(path("d.vtu"), mesh, f, {{"flags", {1, 0, 0, 0, 1}}},
                   {{"quality", {0.5, 0.25}}});
  std::ifstream in(path("d.vtu"));
  const std::string xml((std::istreambuf_iterator<char>(in)), {});
  for (const char* fragment :
       {"<VTKFile type=\"UnstructuredGrid\"", "NumberOfPoints=\"5\" NumberOfCells=\"2\"",
        "Name=\"f\" format=\"ascii\">\n-1\n0.5\n0.3333333333333333\n2\n1e-300\n", "Name=\"flags\"",
        "Name=\"quality\" format=\"ascii\">\n0.5\n0.25\n",
        "Name=\"connectivity\" format=\"ascii\">\n0 1 2 3\n1 2 3 4\n",
        "Name=\"offsets\" format=\"ascii\">\n4\n8\n", "Name=\"types\" format=\"ascii\">\n10\n10\n",
        "NumberOfComponents=\"3\" format=\"ascii\">\n0 0 0\n1 0 0\n", "</VTKFile>\n"}) {
    EXPECT_NE(xml.find(fragment), std::string::npos) << fragment;
  }
  // Balanced tags.
  for (const char* tag :
       {"VTKFile", "UnstructuredGrid", "Piece", "PointData", "CellData", "Points", "Cells"}) {
    EXPECT_NE(xml.find("<" + std::string(tag)), std::string::npos) << tag;
    EXPECT_NE(xml.find("</" + std::string(tag) + ">"), std::string::npos) << tag;
  }
  EXPECT_THROW(write_domain_vtu(path("e.vtu"), mesh, {1, 2}), std::invalid_argument);
  EXPECT_THROW(write_domain_vtu(path("e.vtu"), mesh, f, {}, {{"q", {1}}}), std::invalid_argument);
  expect_input_error([&] { write_domain_vtu(path("e.vtk"), mesh, f); },
                     {path("e.vtk"), "expected one of .vtu"});
  EXPECT_EQ(entries(), std::vector<std::string>{"d.vtu"});
}

// ------------------------------------------------------------ attributes

// A tetrahedron's mesh with a colour (red, green, blue as `type`) and two other properties.
TriangleMesh coloured_tetrahedron(const std::string& type) {
  TriangleMesh m = awkward_tetrahedron();
  const double top = type == "uchar" ? 255 : 1;
  m.attributes = {{"red", type, {0, top, top / 5, top}},
                  {"green", type, {top, 0, top / 5, top}},
                  {"blue", type, {0, 0, top, top}},
                  {"intensity", "float", {0.5, -1.25, 3, 1e-3}},
                  {"segment_index", "int", {0, 7, -3, 2000000000}}};
  return m;
}

TEST_F(IoTest, PlyRoundTripsKeepColoursAndOtherProperties) {
  for (const std::string type : {"uchar", "float", "double"})
    for (const bool ascii : {false, true}) {
      const TriangleMesh m = coloured_tetrahedron(type);
      write_mesh(path("c.ply"), m, {ascii});
      const TriangleMesh back = read_mesh(path("c.ply"));
      ASSERT_EQ(back.attributes.size(), m.attributes.size()) << type;
      for (std::size_t a = 0; a < m.attributes.size(); ++a) {
        EXPECT_EQ(back.attributes[a].name, m.attributes[a].name);
        EXPECT_EQ(back.attributes[a].type, m.attributes[a].type);
        for (std::size_t v = 0; v < 4; ++v) {
          const double want = m.attributes[a].type == "uchar"
                                  ? std::round(m.attributes[a].values[v])
                              : m.attributes[a].type == "float"
                                  ? static_cast<float>(m.attributes[a].values[v])
                                  : m.attributes[a].values[v];
          EXPECT_EQ(back.attributes[a].values[v], want) << m.attributes[a].name << " " << v;
        }
      }
      // Point sets too.
      PointSet points = test::sample_sphere(4);
      points.points[3] *= 2;
      points.attributes = m.attributes;
      write_points(path("p.ply"), points, {ascii});
      const PointSet read = read_points(path("p.ply"));
      ASSERT_EQ(read.attributes.size(), m.attributes.size());
      EXPECT_EQ(read.attributes[4].values, back.attributes[4].values);
    }
}

TEST_F(IoTest, OffAndObjCarryTheColours) {
  const TriangleMesh m = coloured_tetrahedron("uchar");
  write_mesh(path("c.off"), m);
  const std::string off = slurp(path("c.off"));
  EXPECT_EQ(off.rfind("COFF\n", 0), 0u) << off;
  EXPECT_NE(off.find(" 0 255 0\n"), std::string::npos) << off;  // red 0, green 255, blue 0
  // Read back: the colours (not the other properties, which OFF and OBJ do not hold).
  const TriangleMesh from_off = read_mesh(path("c.off"));
  EXPECT_EQ(from_off.faces.size(), 4u);
  ASSERT_EQ(from_off.attributes.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(from_off.attributes[c].type, "uchar");
    EXPECT_EQ(from_off.attributes[c].values, m.attributes[c].values);
  }
  write_mesh(path("c.obj"), m);
  const std::string obj = slurp(path("c.obj"));
  EXPECT_NE(obj.find(" 1 0 0\n"), std::string::npos) << obj;  // vertex 2: red 1, green 0, blue 0
  const TriangleMesh from_obj = read_mesh(path("c.obj"));
  EXPECT_EQ(from_obj.faces.size(), 4u);
  ASSERT_EQ(from_obj.attributes.size(), 3u);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(from_obj.attributes[c].values[i] * 255, m.attributes[c].values[i], 1e-4);
  // COFF with 0-1 reals and alpha; an OBJ whose colours stop halfway; a colour out of range.
  write_file("r.off", "COFF\n4 0 0\n0 0 0 1 0.5 0 1\n1 0 0 0 0 1 0.25\n0 1 0 1 1 1 1\n0 0 1 0 0 0 1\n");
  const PointSet reals = read_points(path("r.off"));
  ASSERT_EQ(reals.attributes.size(), 4u);
  EXPECT_EQ(reals.attributes[1].type, "float");
  EXPECT_EQ(reals.attributes[3].name, "alpha");
  EXPECT_EQ(reals.attributes[3].values[1], 0.25);
  ValidationReport report;
  write_file("h.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0\nv 0 0 1\n");
  EXPECT_TRUE(read_points(path("h.obj"), &report).attributes.empty());
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0], path("h.obj") +
                                    ": the vertex colours (v x y z r g b) are not read: 2 of "
                                    "the 4 vertices have one");
  write_file("o.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 2 0\nv 0 1 0 0 0 1\nv 0 0 1 1 1 1\n");
  expect_input_error([&] { read_points(path("o.obj")); },
                     {path("o.obj"), "line 2", "'green' is 2, outside 0-1"});
}

TEST_F(IoTest, BadColoursAreNamed) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\n";
  const std::string points[4] = {"0 0 0", "1 0 0", "0 1 0", "0 0 1"};
  auto file = [&](const std::string& properties, const std::string& values) {
    std::string text = head + properties + "end_header\n";
    for (const std::string& p : points) text += p + " " + values + "\n";
    return text;
  };
  const std::string floats = "property float red\nproperty float green\nproperty float blue\n";
  write_file("c.ply", file(floats, "0.5 1.5 0"));
  expect_input_error([&] { read_points(path("c.ply")); },
                     {path("c.ply"), "line 11 (point 1)", "'green'", "1.5", "outside 0-1"});
  write_file("c.ply",
             file("property int red\nproperty uchar green\nproperty uchar blue\n", "1 2 3"));
  expect_input_error([&] { read_points(path("c.ply")); },
                     {path("c.ply"), "'red' is int", "uchar (0-255)"});
  write_file("c.ply", file(floats, "nan 0 0"));
  expect_input_error([&] { read_points(path("c.ply")); }, {"'red' is nan", "outside 0-1"});
  // A lone channel, or an unknown property, is no colour: read as it is.
  write_file("c.ply", file("property int red\nproperty float confidence\n", "-4 0.5"));
  const PointSet lone = read_points(path("c.ply"));
  ASSERT_EQ(lone.attributes.size(), 2u);
  EXPECT_EQ(lone.attributes[0].values[3], -4);
  // A point set from memory gets the same checks.
  PointSet p = test::sample_sphere(10);
  p.attributes = {{"red", "uchar", std::vector<double>(10, 1)},
                  {"green", "uchar", std::vector<double>(10, 300)},
                  {"blue", "uchar", std::vector<double>(10, 1)}};
  expect_input_error([&] { validate_points(p, "mine"); }, {"mine: point 1", "'green' is 300"});
  p.attributes.resize(1);
  p.attributes[0].values.resize(9);
  expect_input_error([&] { validate_points(p, "mine"); }, {"'red' has 9 values for 10 points"});
  // Any property's values must be ones its type holds.
  p.attributes = {{"label", "uchar", std::vector<double>(10, 2.5)}};
  expect_input_error([&] { validate_points(p, "mine"); },
                     {"mine: point 1", "'label' is a uchar, which cannot hold 2.5"});
}

TEST_F(IoTest, MergedDuplicatesTakeTheirAttributesWithThem) {
  PointSet p = test::sample_sphere(10);
  p.points.push_back(p.points[3]);
  p.normals.push_back(p.normals[3]);
  p.attributes = {{"intensity", "float", {}}};
  for (int i = 0; i < 11; ++i) p.attributes[0].values.push_back(i);
  const PointSet merged = validate_points(p, "mine");
  ASSERT_EQ(merged.size(), 10u);
  ASSERT_EQ(merged.attributes[0].values.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(merged.attributes[0].values[i], i);
}

}  // namespace
}  // namespace pdd
