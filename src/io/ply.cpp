// PLY (Turk's polygon file format): ASCII and binary of either byte order.
// Reads the "vertex" element (x y z, optional nx ny nz, and every other scalar
// property as an attribute) and, for meshes, the "face" element's
// vertex_indices; every other element and property is
// skipped but still checked for completeness, so that a truncated file or a
// header that does not match the body is reported. ASCII records are read one
// per line, as writers lay them out, so that an error can name its line.
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <optional>
#include <type_traits>

#include "io/formats.h"
#include "io/text.h"

namespace pdd::io {

namespace {

enum class Scalar { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct ScalarName {
  const char* name;
  Scalar type;
};

constexpr ScalarName kScalars[] = {
    {"char", Scalar::kInt8},       {"int8", Scalar::kInt8},       {"uchar", Scalar::kUint8},
    {"uint8", Scalar::kUint8},     {"short", Scalar::kInt16},     {"int16", Scalar::kInt16},
    {"ushort", Scalar::kUint16},   {"uint16", Scalar::kUint16},   {"int", Scalar::kInt32},
    {"int32", Scalar::kInt32},     {"uint", Scalar::kUint32},     {"uint32", Scalar::kUint32},
    {"float", Scalar::kFloat32},   {"float32", Scalar::kFloat32}, {"double", Scalar::kFloat64},
    {"float64", Scalar::kFloat64},
};

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::kInt8:
    case Scalar::kUint8:
      return 1;
    case Scalar::kInt16:
    case Scalar::kUint16:
      return 2;
    case Scalar::kInt32:
    case Scalar::kUint32:
    case Scalar::kFloat32:
      return 4;
    case Scalar::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(Scalar type) { return type != Scalar::kFloat32 && type != Scalar::kFloat64; }

// The canonical name of a type (the first of its two spellings).
const char* type_name(Scalar type) {
  for (const ScalarName& s : kScalars)
    if (s.type == type) return s.name;
  return "float";
}

// The range of an integer type.
std::pair<double, double> integer_range(Scalar type) {
  switch (type) {
    case Scalar::kInt8:
      return {-128.0, 127.0};
    case Scalar::kUint8:
      return {0.0, 255.0};
    case Scalar::kInt16:
      return {-32768.0, 32767.0};
    case Scalar::kUint16:
      return {0.0, 65535.0};
    case Scalar::kInt32:
      return {-2147483648.0, 2147483647.0};
    case Scalar::kUint32:
      return {0.0, 4294967295.0};
    case Scalar::kFloat32:
    case Scalar::kFloat64:
      break;
  }
  return {-HUGE_VAL, HUGE_VAL};
}

Scalar type_named(const std::string& name) {
  for (const ScalarName& s : kScalars)
    if (name == s.name) return s.type;
  return Scalar::kFloat32;
}

// Whether `value` is one a property of `type` holds: a whole number in range
// for the integers, within float's range (or not finite) for a float.
bool holds(Scalar type, double value) {
  if (type == Scalar::kFloat64) return true;
  if (type == Scalar::kFloat32)
    return !std::isfinite(value) || std::abs(value) <= std::numeric_limits<float>::max();
  const auto [lo, hi] = integer_range(type);
  return value == std::floor(value) && value >= lo && value <= hi;
}

struct Property {
  std::string name;
  Scalar type = Scalar::kFloat32;  // of the value, or of the items of a list
  bool is_list = false;
  Scalar count_type = Scalar::kUint8;  // lists only
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  std::size_t line = 0;  // of its "element" line in the header
};

enum class Encoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after "end_header\n"
  std::size_t body_line = 0;    // number of the first line after the header
};

// The properties of the vertex element pdd reads, as indices into its
// property list.
struct VertexLayout {
  std::size_t element = 0;
  std::array<std::size_t, 3> position{};
  std::optional<std::array<std::size_t, 3>> normal;
  std::vector<std::size_t> attributes;  // every other scalar property
  std::vector<char> float_attributes;   // whether each of those is a float (not a double)
};

struct FaceLayout {
  std::size_t element = 0;
  std::size_t indices = 0;
};

Scalar scalar_at(std::string_view name, const std::string& path, std::size_t line) {
  for (const ScalarName& s : kScalars) {
    if (name == s.name) return s.type;
  }
  fail_at_line(path, line, "malformed header: unknown property type " + quote(name));
}

Header parse_header(const std::string& path, const std::string& data) {
  LineReader reader(data, '\0');
  std::vector<std::string_view> tokens;
  if (!reader.next(tokens) || reader.line() != 1 || tokens.size() != 1 || tokens[0] != "ply") {
    fail(path, "not a PLY file: the first line is not 'ply'");
  }
  Header header;
  bool has_format = false;
  while (true) {
    if (!reader.next(tokens)) fail(path, "malformed header: no 'end_header' line");
    const std::size_t line = reader.line();
    for (std::string_view token : tokens) {
      for (char c : token) {
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) {
          fail(path, "malformed header: no 'end_header' line before binary data");
        }
      }
    }
    const std::string_view key = tokens[0];
    if (key == "end_header") {
      if (tokens.size() != 1) fail_at_line(path, line, "malformed header: text after 'end_header'");
      header.body_offset = reader.offset();
      header.body_line = line + 1;
      break;
    }
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (tokens.size() != 3) {
        fail_at_line(path, line, "malformed header: expected 'format <encoding> 1.0'");
      }
      if (tokens[1] == "ascii") {
        header.encoding = Encoding::kAscii;
      } else if (tokens[1] == "binary_little_endian") {
        header.encoding = Encoding::kBinaryLittleEndian;
      } else if (tokens[1] == "binary_big_endian") {
        header.encoding = Encoding::kBinaryBigEndian;
      } else {
        fail_at_line(path, line,
                     "malformed header: unknown format " + quote(tokens[1]) +
                         " (expected ascii, binary_little_endian or "
                         "binary_big_endian)");
      }
      has_format = true;
    } else if (key == "element") {
      std::int64_t count = -1;
      if (tokens.size() != 3 || !parse_integer(tokens[2], count) || count < 0) {
        fail_at_line(path, line, "malformed header: expected 'element <name> <count>'");
      }
      header.elements.push_back(
          {std::string(tokens[1]), static_cast<std::uint64_t>(count), {}, line});
    } else if (key == "property") {
      if (header.elements.empty()) {
        fail_at_line(path, line, "malformed header: 'property' before any 'element'");
      }
      Property property;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.is_list = true;
        property.count_type = scalar_at(tokens[2], path, line);
        if (!is_integer(property.count_type)) {
          fail_at_line(path, line, "malformed header: a list count must have an integer type");
        }
        property.type = scalar_at(tokens[3], path, line);
        property.name = tokens[4];
      } else if (tokens.size() == 3 && tokens[1] != "list") {
        property.type = scalar_at(tokens[1], path, line);
        property.name = tokens[2];
      } else {
        fail_at_line(path, line,
                     "malformed header: expected 'property <type> <name>' or "
                     "'property list <count type> <item type> <name>'");
      }
      header.elements.back().properties.push_back(property);
    } else {
      fail_at_line(path, line, "malformed header: unexpected " + quote(key));
    }
  }
  if (!has_format) fail(path, "malformed header: no 'format' line");
  // A record without properties takes no bytes: nothing bounds its count.
  for (const Element& element : header.elements) {
    if (element.properties.empty() && element.count > 0) {
      fail_at_line(path, element.line,
                   "malformed header: element " + quote(element.name) + " declares " +
                       std::to_string(element.count) + " records but no properties");
    }
  }
  return header;
}

// The fewest bytes a record of `element` takes: its scalars, and the counts
// of its lists (which may be empty); in ASCII, one byte per line is assumed.
std::uint64_t min_record_bytes(const Element& element, Encoding encoding) {
  if (encoding == Encoding::kAscii) return 1;
  std::uint64_t bytes = 0;
  for (const Property& property : element.properties)
    bytes += size_of(property.is_list ? property.count_type : property.type);
  return bytes;
}

// Checks every declared count against the bytes that follow the header,
// before anything is read, so that a count no file could hold fails at once
// instead of after a walk through its records.
void check_counts(const std::string& path, const Header& header, std::size_t body_bytes) {
  std::uint64_t left = body_bytes;
  for (const Element& element : header.elements) {
    const std::uint64_t size = min_record_bytes(element, header.encoding);
    if (size == 0) continue;  // no properties, so no records (read_header checks)
    if (element.count > left / size) {
      const bool ascii = header.encoding == Encoding::kAscii;
      fail_at_line(path, element.line,
                   "file is truncated or its header is wrong: it declares " +
                       std::to_string(element.count) + " " + quote(element.name) +
                       " records of at least " + std::to_string(size) +
                       (ascii ? " byte (a line)" : size == 1 ? " byte" : " bytes") + " each, but only " +
                       std::to_string(left) + " bytes are left for them");
    }
    left -= element.count * size;
  }
}

std::optional<std::size_t> find_property(const Element& element, const char* name) {
  for (std::size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name) return i;
  }
  return std::nullopt;
}

VertexLayout vertex_layout(const std::string& path, const Header& header) {
  VertexLayout layout;
  std::size_t e = 0;
  while (e < header.elements.size() && header.elements[e].name != "vertex") ++e;
  if (e == header.elements.size()) fail(path, "malformed header: no element 'vertex'");
  layout.element = e;
  const Element& vertex = header.elements[e];
  auto scalar_property = [&](const char* name) {
    const auto i = find_property(vertex, name);
    if (i && vertex.properties[*i].is_list) {
      fail(path, std::string("malformed header: vertex property '") + name + "' is a list");
    }
    return i;
  };
  const char* position_names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    const auto i = scalar_property(position_names[k]);
    if (!i)
      fail(path, std::string("malformed header: element 'vertex' has no property '") +
                     position_names[k] + "'");
    layout.position[k] = *i;
  }
  const char* normal_names[3] = {"nx", "ny", "nz"};
  std::array<std::optional<std::size_t>, 3> normal;
  for (int k = 0; k < 3; ++k) normal[k] = scalar_property(normal_names[k]);
  if (normal[0] && normal[1] && normal[2]) {
    layout.normal = std::array<std::size_t, 3>{*normal[0], *normal[1], *normal[2]};
  } else if (normal[0] || normal[1] || normal[2]) {
    fail(path, "malformed header: element 'vertex' has some of nx, ny, nz but not all three");
  }
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    const Property& property = vertex.properties[i];
    const bool read = std::find(layout.position.begin(), layout.position.end(), i) !=
                          layout.position.end() ||
                      (layout.normal && std::find(layout.normal->begin(), layout.normal->end(),
                                                  i) != layout.normal->end());
    if (!read && !property.is_list) {
      layout.attributes.push_back(i);
      layout.float_attributes.push_back(property.type == Scalar::kFloat32);
    }
  }
  return layout;
}

std::optional<FaceLayout> face_layout(const std::string& path, const Header& header) {
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    if (element.name != "face") continue;
    auto i = find_property(element, "vertex_indices");
    if (!i) i = find_property(element, "vertex_index");
    if (!i || !element.properties[*i].is_list) {
      fail(path, "malformed header: element 'face' has no list property 'vertex_indices'");
    }
    return FaceLayout{e, *i};
  }
  return std::nullopt;
}

// Checks a face's vertex count and stores its indices.
void add_face(const std::string& path, std::size_t line, std::uint64_t face,
              const std::vector<double>& indices, RawMesh& mesh) {
  const std::string where = "face " + std::to_string(face + 1);
  if (indices.size() != 3) {
    const std::string what = where + " has " + std::to_string(indices.size()) +
                             " vertices; only triangle meshes are supported";
    if (line) fail_at_line(path, line, what);
    fail(path, what);
  }
  std::array<std::int64_t, 3> f;
  for (int k = 0; k < 3; ++k) {
    if (indices[k] != std::floor(indices[k])) {
      fail(path, where + " has a vertex index that is not an integer");
    }
    // A float list can hold any index; past int64 there is no such vertex.
    if (!(std::abs(indices[k]) < 0x1p63))
      fail(path,
           where + " refers to vertex " + format_double(indices[k]) + ", which cannot exist");
    f[k] = static_cast<std::int64_t>(indices[k]);
  }
  mesh.faces.push_back(f);
  if (line) mesh.face_lines.push_back(line);
}

// Stores the values pdd reads from one vertex record.
void add_vertex(const VertexLayout& layout, const std::vector<double>& values, RawMesh& mesh) {
  const auto& p = layout.position;
  mesh.vertices.points.emplace_back(values[p[0]], values[p[1]], values[p[2]]);
  if (layout.normal) {
    const auto& n = *layout.normal;
    mesh.vertices.normals.emplace_back(values[n[0]], values[n[1]], values[n[2]]);
  }
  // An attribute keeps its type's precision (a text float is rounded to a
  // float), so that it is written back as it was read.
  for (std::size_t a = 0; a < layout.attributes.size(); ++a) {
    const double value = values[layout.attributes[a]];
    mesh.vertices.attributes[a].values.push_back(
        layout.float_attributes[a] ? static_cast<double>(static_cast<float>(value)) : value);
  }
}

void read_ascii_body(const std::string& path, const std::string& data, const Header& header,
                     const VertexLayout& vertex, const std::optional<FaceLayout>& face,
                     RawMesh& mesh) {
  LineReader reader(std::string_view(data).substr(header.body_offset), '\0', header.body_line);
  std::vector<std::string_view> tokens;
  std::vector<double> values;   // one per scalar property
  std::vector<double> indices;  // the items of the face list
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    const bool is_vertex = e == vertex.element;
    const bool is_face = face && e == face->element;
    for (std::uint64_t r = 0; r < element.count; ++r) {
      if (!reader.next(tokens)) {
        fail(path, "file is truncated: it ends after " + std::to_string(r) + " of the " +
                       std::to_string(element.count) + " " + quote(element.name) +
                       " records the header declares");
      }
      const std::size_t line = reader.line();
      const std::string record = quote(element.name) + " record " + std::to_string(r + 1);
      std::size_t t = 0;
      values.assign(element.properties.size(), 0.0);
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (t >= tokens.size()) {
          fail_at_line(path, line, record + " has too few values for its properties");
        }
        if (!property.is_list) {
          const std::string_view token = tokens[t++];
          values[p] = double_at(token, path, line);
          // A text value must be one its property's type can hold, as a binary one is.
          if (!holds(property.type, values[p]))
            fail_at_line(path, line,
                         record + ": property " + quote(property.name) + " is a " +
                             type_name(property.type) + ", which cannot hold " + quote(token));
          continue;
        }
        const std::string_view count_token = tokens[t++];
        const std::int64_t count = integer_at(count_token, path, line);
        if (!holds(property.count_type, static_cast<double>(count)))
          fail_at_line(path, line,
                       record + ": the count of list " + quote(property.name) + " is a " +
                           type_name(property.count_type) + ", which cannot hold " +
                           quote(count_token));
        if (count < 0 || static_cast<std::uint64_t>(count) > tokens.size() - t) {
          fail_at_line(path, line,
                       record + " has a list of " + std::to_string(count) +
                           " items but fewer values follow");
        }
        const bool keep = is_face && p == face->indices;
        if (keep) indices.clear();
        for (std::int64_t k = 0; k < count; ++k) {
          const std::string_view token = tokens[t++];
          const double item = double_at(token, path, line);
          if (!holds(property.type, item))
            fail_at_line(path, line,
                         record + ": the items of list " + quote(property.name) + " are " +
                             type_name(property.type) + "s, which cannot hold " + quote(token));
          if (keep) indices.push_back(item);
        }
      }
      if (t != tokens.size()) {
        fail_at_line(path, line,
                     record + " has " + std::to_string(tokens.size() - t) +
                         " more values than its properties");
      }
      if (is_vertex) {
        add_vertex(vertex, values, mesh);
        mesh.vertices.lines.push_back(line);
      }
      if (is_face) add_face(path, line, r, indices, mesh);
    }
  }
  if (reader.next(tokens)) {
    fail_at_line(path, reader.line(), "data after the last element the header declares");
  }
}

// Reads binary scalars of either byte order.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& data, std::size_t offset, bool swap)
      : data_(data), pos_(offset), swap_(swap) {}
  std::size_t remaining() const { return data_.size() - pos_; }
  void skip(std::size_t bytes) { pos_ += bytes; }
  // The next value; the caller has checked that enough bytes remain.
  double read(Scalar type) {
    unsigned char bytes[8];
    const std::size_t size = size_of(type);
    std::memcpy(bytes, data_.data() + pos_, size);
    pos_ += size;
    if (swap_) std::reverse(bytes, bytes + size);
    switch (type) {
      case Scalar::kInt8:
        return as<std::int8_t>(bytes);
      case Scalar::kUint8:
        return as<std::uint8_t>(bytes);
      case Scalar::kInt16:
        return as<std::int16_t>(bytes);
      case Scalar::kUint16:
        return as<std::uint16_t>(bytes);
      case Scalar::kInt32:
        return as<std::int32_t>(bytes);
      case Scalar::kUint32:
        return as<std::uint32_t>(bytes);
      case Scalar::kFloat32:
        return as<float>(bytes);
      case Scalar::kFloat64:
        return as<double>(bytes);
    }
    return 0;
  }

 private:
  template <class T>
  static double as(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }

  const std::string& data_;
  std::size_t pos_;
  bool swap_;
};

void read_binary_body(const std::string& path, const std::string& data, const Header& header,
                      const VertexLayout& vertex, const std::optional<FaceLayout>& face,
                      RawMesh& mesh) {
  const bool file_little = header.encoding == Encoding::kBinaryLittleEndian;
  BinaryCursor cursor(data, header.body_offset, file_little != host_is_little_endian());
  std::vector<double> values;
  std::vector<double> indices;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    const bool is_vertex = e == vertex.element;
    const bool is_face = face && e == face->element;
    auto truncated = [&](std::uint64_t record) {
      fail(path, "file is truncated: it ends inside " + quote(element.name) + " record " +
                     std::to_string(record + 1) + " of the " + std::to_string(element.count) +
                     " the header declares");
    };
    std::size_t fixed_size = 0;  // bytes per record, 0 when it holds a list
    for (const Property& property : element.properties) {
      if (property.is_list) {
        fixed_size = 0;
        break;
      }
      fixed_size += size_of(property.type);
    }
    if (fixed_size > 0 && !is_vertex && !is_face) {  // skipped whole
      if (element.count > cursor.remaining() / fixed_size) {
        truncated(cursor.remaining() / fixed_size);
      }
      cursor.skip(element.count * fixed_size);
      continue;
    }
    for (std::uint64_t r = 0; r < element.count; ++r) {
      values.assign(element.properties.size(), 0.0);
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.is_list) {
          if (cursor.remaining() < size_of(property.type)) truncated(r);
          values[p] = cursor.read(property.type);
          continue;
        }
        if (cursor.remaining() < size_of(property.count_type)) truncated(r);
        const double count = cursor.read(property.count_type);
        if (count < 0) {
          fail(path, quote(element.name) + " record " + std::to_string(r + 1) +
                         " has a negative list length");
        }
        const auto n = static_cast<std::uint64_t>(count);
        if (n > cursor.remaining() / size_of(property.type)) truncated(r);
        const bool keep = is_face && p == face->indices;
        if (!keep) {
          cursor.skip(n * size_of(property.type));
          continue;
        }
        indices.clear();
        for (std::uint64_t k = 0; k < n; ++k) indices.push_back(cursor.read(property.type));
      }
      if (is_vertex) add_vertex(vertex, values, mesh);
      if (is_face) add_face(path, 0, r, indices, mesh);
    }
  }
  if (cursor.remaining() > 0) {
    fail(path, std::to_string(cursor.remaining()) +
                   " bytes of data after the last element the header declares");
  }
}

void append_binary(std::string& out, const void* value, std::size_t size, bool swap) {
  unsigned char bytes[8];
  std::memcpy(bytes, value, size);
  if (swap) std::reverse(bytes, bytes + size);
  out.append(reinterpret_cast<const char*>(bytes), size);
}

}  // namespace

RawMesh read_ply(const std::string& path, const std::string& data, Content content) {
  const Header header = parse_header(path, data);
  const VertexLayout vertex = vertex_layout(path, header);
  std::optional<FaceLayout> face;
  if (content == Content::kVerticesAndFaces) {
    face = face_layout(path, header);
    if (!face) fail(path, "no element 'face': the file holds no mesh");
  }
  const std::size_t body = data.size() - header.body_offset;
  check_counts(path, header, body);
  RawMesh mesh;
  for (std::size_t i : vertex.attributes) {
    const Property& property = header.elements[vertex.element].properties[i];
    mesh.vertices.attributes.push_back({property.name, type_name(property.type), {}});
  }
  // Reserve no more than the body could hold, whatever the header claims.
  mesh.vertices.points.reserve(
      std::min<std::uint64_t>(header.elements[vertex.element].count, body / 3));
  if (header.encoding == Encoding::kAscii) {
    read_ascii_body(path, data, header, vertex, face, mesh);
  } else {
    read_binary_body(path, data, header, vertex, face, mesh);
  }
  return mesh;
}

void write_ply(std::ostream& out, const std::vector<Vec3>& vertices,
               const std::vector<Vec3>& normals, const std::vector<Attribute>& attributes,
               const Faces* faces, bool ascii) {
  std::string text = "ply\nformat ";
  text += ascii ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
  text += "comment written by pdd " PDD_VERSION "\n";
  text += "element vertex " + std::to_string(vertices.size()) + "\n";
  // Doubles, so that positions read back bit for bit.
  for (const char* name : {"x", "y", "z"}) text += std::string("property double ") + name + "\n";
  if (!normals.empty()) {
    for (const char* name : {"nx", "ny", "nz"}) {
      text += std::string("property double ") + name + "\n";
    }
  }
  std::vector<Scalar> attribute_types;
  for (const Attribute& a : attributes) {
    attribute_types.push_back(type_named(a.type));
    text += "property " + std::string(type_name(attribute_types.back())) + " " + a.name + "\n";
  }
  if (faces) {
    text += "element face " + std::to_string(faces->size()) + "\n";
    text += "property list uchar int vertex_indices\n";
  }
  text += "end_header\n";
  out.write(text.data(), static_cast<std::streamsize>(text.size()));

  const bool swap = !host_is_little_endian();
  std::string chunk;
  auto flush_chunk = [&](bool force) {
    if (force || chunk.size() > (1u << 16)) {
      out.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
      chunk.clear();
    }
  };
  auto put_vector = [&](const Vec3& v) {
    for (int k = 0; k < 3; ++k) {
      if (ascii) {
        if (k > 0) chunk += ' ';
        append_double(chunk, v[k]);
      } else {
        append_binary(chunk, &v[k], sizeof(double), swap);
      }
    }
  };
  // An attribute's value in its type; integers are rounded (interpolated
  // values of an integer property lie within its range).
  auto put_scalar = [&](Scalar type, double value) {
    if (ascii) chunk += ' ';
    auto put = [&](auto typed) {
      if (ascii) {
        if constexpr (std::is_integral_v<decltype(typed)>) {
          chunk += std::to_string(typed);
        } else {
          append_double(chunk, static_cast<double>(typed));
        }
      } else {
        append_binary(chunk, &typed, sizeof(typed), swap);
      }
    };
    const double r = std::round(value);
    switch (type) {
      case Scalar::kInt8: put(static_cast<std::int8_t>(r)); break;
      case Scalar::kUint8: put(static_cast<std::uint8_t>(r)); break;
      case Scalar::kInt16: put(static_cast<std::int16_t>(r)); break;
      case Scalar::kUint16: put(static_cast<std::uint16_t>(r)); break;
      case Scalar::kInt32: put(static_cast<std::int32_t>(r)); break;
      case Scalar::kUint32: put(static_cast<std::uint32_t>(r)); break;
      case Scalar::kFloat32: put(static_cast<float>(value)); break;
      case Scalar::kFloat64: put(value); break;
    }
  };
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    put_vector(vertices[i]);
    if (!normals.empty()) {
      if (ascii) chunk += ' ';
      put_vector(normals[i]);
    }
    for (std::size_t a = 0; a < attributes.size(); ++a)
      put_scalar(attribute_types[a], attributes[a].values[i]);
    if (ascii) chunk += '\n';
    flush_chunk(false);
  }
  if (faces) {
    for (std::size_t i = 0; i < faces->size(); ++i) {
      const auto& face = (*faces)[i];
      check_face(face, i, vertices.size());
      if (ascii) {
        chunk += "3 " + std::to_string(face[0]) + ' ' + std::to_string(face[1]) + ' ' +
                 std::to_string(face[2]) + '\n';
      } else {
        chunk += static_cast<char>(3);
        for (int k = 0; k < 3; ++k) {
          const std::int32_t index = face[k];
          append_binary(chunk, &index, sizeof(index), swap);
        }
      }
      flush_chunk(false);
    }
  }
  flush_chunk(true);
}

std::vector<Attribute> colour_attributes(const std::vector<std::array<double, 4>>& rows,
                                         int channels, bool integers) {
  std::vector<Attribute> out;
  const char* const names[] = {"red", "green", "blue", "alpha"};
  for (int c = 0; c < channels; ++c) {
    Attribute a{names[c], integers ? "uchar" : "float", {}};
    a.values.reserve(rows.size());
    for (const auto& row : rows)
      a.values.push_back(integers ? row[c] : static_cast<double>(static_cast<float>(row[c])));
    out.push_back(std::move(a));
  }
  return out;
}

std::vector<const Attribute*> colour_channels(const std::vector<Attribute>& attributes) {
  std::vector<const Attribute*> channels;
  for (const char* name : {"red", "green", "blue", "alpha"})
    for (const Attribute& a : attributes)
      if (a.name == name) channels.push_back(&a);
  if (channels.size() < 3) channels.clear();
  return channels;
}

double unit_colour(const Attribute& channel, double value) {
  if (channel.type == "uchar") return value / 255;
  if (channel.type == "ushort") return value / 65535;
  return value;
}

bool type_holds(const std::string& type, double value) { return holds(type_named(type), value); }

}  // namespace pdd::io
