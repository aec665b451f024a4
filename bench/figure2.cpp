// Figure 2 of the paper, reproduced (§2.2): contour the analytic unit sphere
// f(x) = |x| - 1 on four two-layer domains and compare the triangles.
//
//   figure2 [points_per_layer ...] [--output PATH]
//
// Defaults: 250 and 4000 points per layer; writes bench/results/figure2.txt
// (relative to the working directory).
#include <pdd/contour.h>
#include <pdd/quality.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "support/figure2_layouts.h"

namespace {

using pdd::test::Figure2Layout;

std::string row(const std::vector<std::string>& cells, const std::vector<int>& widths) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    std::string cell = cells[i];
    if (cell.size() < static_cast<std::size_t>(widths[i]))
      cell = (i == 0 ? cell + std::string(widths[i] - cell.size(), ' ')
                     : std::string(widths[i] - cell.size(), ' ') + cell);
    line += (i ? " | " : "| ") + cell;
  }
  return line + " |\n";
}

std::string fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

// The table for one size: one row per layout.
std::string table(int points_per_layer) {
  const std::vector<int> widths = {27, 6, 9, 9, 8, 6, 6, 6, 6, 8, 7, 12, 5};
  std::string out = "points per layer: " + std::to_string(points_per_layer) + "\n\n";
  out += row({"layout", "tets", "crossing", "triangles", "mean min", "min", "< 10", "< 20", "< 30",
              "tet dihed", "tet r/e", "closed/euler", "ms"},
             widths);
  out += row({"---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:",
              "---:", "---:"},
             widths);
  for (const Figure2Layout layout :
       {Figure2Layout::kBiasedRandom, Figure2Layout::kUnbiasedRandom, Figure2Layout::kBiasedEven,
        Figure2Layout::kUnbiasedEven, Figure2Layout::kUnbiasedEvenAligned}) {
    const auto start = std::chrono::steady_clock::now();
    const pdd::Domain domain = pdd::test::figure2_domain(layout, points_per_layer);
    const pdd::TetMesh mesh = domain.mesh();
    const pdd::IsoSurface surface = pdd::marching_tetrahedra(mesh, domain.f());
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const pdd::TriangleQuality q = pdd::triangle_quality(surface.mesh);
    const pdd::SurfaceTopology topology = pdd::surface_topology(surface.mesh);
    // The tets crossed by f = 0 (facet_tet is in tet order, both halves of a
    // quadrangle next to each other).
    pdd::TetMesh crossing{mesh.vertices, {}};
    for (std::size_t i = 0; i < surface.facet_tet.size(); ++i)
      if (i == 0 || surface.facet_tet[i] != surface.facet_tet[i - 1])
        crossing.tets.push_back(mesh.tets[surface.facet_tet[i]]);
    const pdd::TetQuality tq = pdd::tet_quality(crossing);
    out += row(
        {pdd::test::figure2_label(layout), std::to_string(domain.num_tets()),
         std::to_string(crossing.tets.size()), std::to_string(q.count), fixed(q.mean_min_angle, 1),
         fixed(q.min_angle, 1), fixed(100 * q.fraction_below_10, 1) + "%",
         fixed(100 * q.fraction_below_20, 1) + "%", fixed(100 * q.fraction_below_30, 1) + "%",
         fixed(tq.mean_min_dihedral, 1), fixed(tq.mean_radius_edge, 2),
         std::string(topology.closed && topology.manifold ? "yes" : "NO") + " / " +
             std::to_string(topology.euler_characteristic),
         fixed(ms, 0)},
        widths);
  }
  return out + "\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  std::string output = "bench/results/figure2.txt";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--output" && i + 1 < argc) {
      output = argv[++i];
    } else {
      try {
        sizes.push_back(std::stoi(arg));
      } catch (const std::exception&) {
        std::cerr << "usage: figure2 [points_per_layer ...] [--output PATH]\n";
        return 2;
      }
    }
  }
  if (sizes.empty()) sizes = {250, 4000};

  std::ostringstream report;
  report
      << "Figure 2: marching tetrahedra on f(x) = |x| - 1 over two-layer Delaunay domains.\n"
      << "Angles in degrees; '< 10' etc. = fraction of triangles whose smallest angle is below;\n"
      << "'crossing' = tets cut by f = 0; 'tet dihed' = their mean smallest dihedral angle and\n"
      << "'tet r/e' their mean radius-edge ratio (regular tet: 70.5 and 0.61);\n"
      << "'ms' = Delaunay + contouring time. (d') = (d) without staggering the layers.\n\n";
  for (const int n : sizes) report << table(n);
  std::cout << report.str();

  const std::filesystem::path path(output);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream file(path);
  file << report.str();
  if (!file) {
    std::cerr << "figure2: cannot write " << output << "\n";
    return 1;
  }
  std::cout << "written to " << output << "\n";
  return 0;
}
