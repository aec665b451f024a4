// The report of `pdd quality` and pdd.quality(): triangle quality and surface
// checks of a mesh, as text or JSON.
#include <pdd/errors.h>
#include <pdd/report.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "common/json.h"

namespace pdd {
namespace {

std::string json(const std::string& path, const TriangleMesh& mesh, const TriangleQuality& q,
                 const SurfaceTopology& s) {
  std::ostringstream o;
  const auto& h = q.min_angle_histogram;
  o << "{\n"
    << "  \"file\": " << json_string(path) << ",\n"
    << "  \"vertices\": " << mesh.vertices.size() << ",\n"
    << "  \"faces\": " << mesh.faces.size() << ",\n"
    << "  \"triangles\": {\n"
    << "    \"count\": " << q.count << ",\n"
    << "    \"min_angle\": " << number(q.min_angle, 6) << ",\n"
    << "    \"mean_min_angle\": " << number(q.mean_min_angle, 6) << ",\n"
    << "    \"max_angle\": " << number(q.max_angle, 6) << ",\n"
    << "    \"fraction_min_angle_below_10\": " << number(q.fraction_below_10, 6) << ",\n"
    << "    \"fraction_min_angle_below_20\": " << number(q.fraction_below_20, 6) << ",\n"
    << "    \"fraction_min_angle_below_30\": " << number(q.fraction_below_30, 6) << ",\n"
    << "    \"min_angle_histogram\": {\"lower\": " << number(h.lower, 6)
    << ", \"bin_width\": " << number(h.bin_width, 6) << ", \"counts\": [";
  for (std::size_t i = 0; i < h.counts.size(); ++i) o << (i ? ", " : "") << h.counts[i];
  o << "]}\n"
    << "  },\n"
    << "  \"surface\": {\n"
    << "    \"vertices\": " << s.vertices << ",\n"
    << "    \"edges\": " << s.edges << ",\n"
    << "    \"faces\": " << s.faces << ",\n"
    << "    \"boundary_edges\": " << s.boundary_edges << ",\n"
    << "    \"non_manifold_edges\": " << s.non_manifold_edges << ",\n"
    << "    \"inconsistent_edges\": " << s.inconsistent_edges << ",\n"
    << "    \"degenerate_faces\": " << s.degenerate_faces << ",\n"
    << "    \"non_manifold_vertices\": " << s.non_manifold_vertices << ",\n"
    << "    \"components\": " << s.components << ",\n"
    << "    \"euler_characteristic\": " << s.euler_characteristic << ",\n"
    << "    \"edge_manifold\": " << (s.edge_manifold ? "true" : "false") << ",\n"
    << "    \"manifold\": " << (s.manifold ? "true" : "false") << ",\n"
    << "    \"closed\": " << (s.closed ? "true" : "false") << ",\n"
    << "    \"genus\": " << (s.genus >= 0 ? std::to_string(s.genus) : "null") << "\n"
    << "  }\n"
    << "}\n";
  return o.str();
}

std::string text(const std::string& path, const TriangleMesh& mesh, const TriangleQuality& q,
                 const SurfaceTopology& s) {
  std::ostringstream o;
  auto line = [&o](const std::string& name, const std::string& value) {
    o << "  " << name << std::string(name.size() < 30 ? 30 - name.size() : 1, ' ') << value << "\n";
  };
  auto percent = [](double fraction) { return number(100 * fraction, 2) + " %"; };
  auto yes = [](bool b) { return std::string(b ? "yes" : "no"); };
  o << path << ": " << mesh.vertices.size() << " vertices, " << mesh.faces.size() << " faces\n"
    << "triangles (angles in degrees)\n";
  line("min angle", number(q.min_angle, 2));
  line("mean min angle", number(q.mean_min_angle, 2));
  line("max angle", number(q.max_angle, 2));
  line("min angle < 10", percent(q.fraction_below_10));
  line("min angle < 20", percent(q.fraction_below_20));
  line("min angle < 30", percent(q.fraction_below_30));
  o << "  min angle histogram\n";
  const Histogram& h = q.min_angle_histogram;
  for (std::size_t i = 0; i < h.counts.size(); ++i) {
    const double lo = h.lower + h.bin_width * i;
    const double fraction = q.count ? static_cast<double>(h.counts[i]) / q.count : 0.0;
    char bin[96];
    std::snprintf(bin, sizeof bin, "    %3.0f - %-3.0f %21zu  (%s)\n", lo, lo + h.bin_width,
                  h.counts[i], percent(fraction).c_str());
    o << bin;
  }
  o << "surface\n";
  line("vertices (referenced)", std::to_string(s.vertices));
  line("edges", std::to_string(s.edges));
  line("faces", std::to_string(s.faces));
  line("euler characteristic", std::to_string(s.euler_characteristic));
  line("components", std::to_string(s.components));
  line("boundary edges", std::to_string(s.boundary_edges));
  line("non-manifold edges", std::to_string(s.non_manifold_edges));
  line("inconsistently oriented edges", std::to_string(s.inconsistent_edges));
  line("degenerate faces", std::to_string(s.degenerate_faces));
  line("non-manifold vertices", std::to_string(s.non_manifold_vertices));
  line("edge-manifold", yes(s.edge_manifold));
  line("manifold", yes(s.manifold));
  line("closed", yes(s.closed));
  line("genus", s.genus >= 0 ? std::to_string(s.genus) : "n/a (open or not manifold)");
  return o.str();
}

}  // namespace

std::string quality_report(const std::string& file, const TriangleMesh& mesh, bool as_json) {
  require_measurable(mesh, file);
  const TriangleQuality q = triangle_quality(mesh);
  // A NaN or an overflow is never reported as a result.
  for (const double v : {q.min_angle, q.mean_min_angle, q.max_angle})
    if (!std::isfinite(v))
      throw InputError(file + ": the triangles' angles come out " +
                       (std::isnan(v) ? "NaN" : "infinite") +
                       "; the coordinates are out of the range they can be computed in");
  const SurfaceTopology s = surface_topology(mesh);
  return as_json ? json(file, mesh, q, s) : text(file, mesh, q, s);
}

}  // namespace pdd
