// The discrete domain (§2.2) as a VTK XML UnstructuredGrid (.vtu), ASCII:
// points, VTK_TETRA cells, the implicit function f per vertex and any extra
// point or cell data. ParaView and VTK's vtkXMLUnstructuredGridReader read it.
#include <pdd/io.h>

#include <cmath>
#include <ostream>
#include <stdexcept>

#include "io/formats.h"
#include "io/text.h"

namespace pdd {

namespace {

constexpr int kVtkTetra = 10;

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// VTK's ASCII reader does not parse "nan" or "inf": such values are refused.
void check_array(const std::string& name, const std::vector<double>& values, std::size_t expected,
                 const char* kind) {
  if (values.size() != expected) {
    throw std::invalid_argument("write_domain_vtu: " + std::string(kind) + " data '" + name +
                                "' has " + std::to_string(values.size()) + " values for " +
                                std::to_string(expected) + " " + kind + "s");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument("write_domain_vtu: " + std::string(kind) + " data '" + name +
                                  "' value " + std::to_string(i) + " is not finite");
    }
  }
}

class XmlText {
 public:
  explicit XmlText(std::ostream& out) : out_(out) {}
  std::string& text() { return text_; }
  void flush(bool force = false) {
    if (force || text_.size() > (1u << 16)) {
      out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
      text_.clear();
    }
  }
  void data_array(const std::string& name, const std::vector<double>& values) {
    text_ += "        <DataArray type=\"Float64\" Name=\"" + xml_escaped(name) +
             "\" format=\"ascii\">\n";
    for (double value : values) {
      io::append_double(text_, value);
      text_ += '\n';
      flush();
    }
    text_ += "        </DataArray>\n";
  }

 private:
  std::ostream& out_;
  std::string text_;
};

}  // namespace

void write_domain_vtu(const std::string& path, const TetMesh& mesh, const std::vector<double>& f,
                      const std::vector<DataArray>& point_data,
                      const std::vector<DataArray>& cell_data, StagedOutputs* staged) {
  io::format_of(path, {io::Format::kVtu}, "domain");
  const std::size_t n = mesh.vertices.size();
  check_array("f", f, n, "point");
  for (const DataArray& a : point_data) check_array(a.name, a.values, n, "point");
  for (const DataArray& a : cell_data) check_array(a.name, a.values, mesh.tets.size(), "cell");
  for (std::size_t i = 0; i < n; ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw std::invalid_argument("write_domain_vtu: vertex " + std::to_string(i) +
                                  " is not finite");
    }
  }
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    for (int v : mesh.tets[t]) {
      if (v < 0 || static_cast<std::size_t>(v) >= n) {
        throw std::invalid_argument("write_domain_vtu: tet " + std::to_string(t) +
                                    " refers to vertex " + std::to_string(v) + " of " +
                                    std::to_string(n));
      }
    }
  }

  io::write_output(path, staged, [&](std::ostream& out) {
    XmlText xml(out);
    std::string& s = xml.text();
    s += "<?xml version=\"1.0\"?>\n";
    s += "<!-- written by pdd " PDD_VERSION " -->\n";
    s += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
    s += "  <UnstructuredGrid>\n";
    s += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" +
         std::to_string(mesh.tets.size()) + "\">\n";
    s += "      <PointData Scalars=\"f\">\n";
    xml.data_array("f", f);
    for (const DataArray& a : point_data) xml.data_array(a.name, a.values);
    s += "      </PointData>\n";
    s += "      <CellData>\n";
    for (const DataArray& a : cell_data) xml.data_array(a.name, a.values);
    s += "      </CellData>\n";
    s += "      <Points>\n";
    s += "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& p : mesh.vertices) {
      io::append_double(s, p.x());
      s += ' ';
      io::append_double(s, p.y());
      s += ' ';
      io::append_double(s, p.z());
      s += '\n';
      xml.flush();
    }
    s += "        </DataArray>\n";
    s += "      </Points>\n";
    s += "      <Cells>\n";
    // Tets are positively oriented (types.h), which is VTK_TETRA's order:
    // the first three vertices seen counter-clockwise from the fourth.
    s += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& tet : mesh.tets) {
      s += std::to_string(tet[0]) + ' ' + std::to_string(tet[1]) + ' ' + std::to_string(tet[2]) +
           ' ' + std::to_string(tet[3]) + '\n';
      xml.flush();
    }
    s += "        </DataArray>\n";
    s += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t t = 1; t <= mesh.tets.size(); ++t) {
      s += std::to_string(4 * t) + '\n';
      xml.flush();
    }
    s += "        </DataArray>\n";
    s += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      s += std::to_string(kVtkTetra) + '\n';
      xml.flush();
    }
    s += "        </DataArray>\n";
    s += "      </Cells>\n";
    s += "    </Piece>\n";
    s += "  </UnstructuredGrid>\n";
    s += "</VTKFile>\n";
    xml.flush(true);
  });
}

}  // namespace pdd
