// The memory budget of a run (ReconstructOptions::max_memory).
#include "pipeline/memory_budget.h"

#include <pdd/errors.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "common/quote.h"

namespace pdd {
namespace detail {
namespace {

// Measured peaks (docs/benchmarks.md, "Memory and the budget"): per vertex of
// the final domain, the solve's matrices, its multigrid levels and the domain
// (1.1-1.5 KB with SSD, 1.4 KB with the spectral solver: 1.5x kept in hand);
// per input point, the points, their kd-trees and locations; and a floor.
constexpr double kBytesPerVertex = 2300;
constexpr double kBytesPerPoint = 500;
constexpr double kBaseBytes = 150e6;
// Final domain vertices per target-sized isofacet (the sum of area / target
// over the isofacets): 0.62 on bunny_clean, 0.71 on fandisk_noise10. The sum
// is within 1.05x of its final value once there are 2000 isofacets (1.35x
// over the first 200).
constexpr double kVerticesPerTargetFacet = 0.75;
constexpr int kMinFacetsToPredict = 2000;
// Refinement stops at this share of the vertex budget: a late pass adds at
// most about half (building.ply: 224k -> 342k -> 393k vertices).
constexpr double kRefineBelow = 0.75;
constexpr std::size_t kMinVertices = 20000;
// The default sizing's cap in proportion to the input: output triangles per
// point and a floor, and output triangles per final domain vertex (2.4 on the
// kitten, 2.0-2.9 on the shared data). The 20k-point inputs give 5 triangles
// per point, their 2k-point sparse variants 38; four points once gave 450k.
constexpr double kTrianglesPerPoint = 60;
constexpr double kMinTriangles = 5000;
constexpr double kTrianglesPerVertex = 2;

std::string megabytes(double bytes) {
  return std::to_string(static_cast<long long>(std::ceil(bytes / (1 << 20)))) + " MB";
}

}  // namespace

std::size_t default_memory_budget() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kb = 0;
  while (meminfo >> key >> kb) {
    if (key == "MemAvailable:") return kb * 1024 / 4 * 3;
    meminfo.ignore(256, '\n');
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * page / 4 * 3 : 0;
}

VertexBudget::VertexBudget(std::size_t bytes, std::size_t num_points, bool in_proportion) {
  report_.bytes = bytes > 0 ? bytes : default_memory_budget();
  const double fixed = kBaseBytes + kBytesPerPoint * static_cast<double>(num_points);
  const double needed = fixed + kBytesPerVertex * kMinVertices;
  if (static_cast<double>(report_.bytes) < needed)
    throw InputError("the memory budget, " + megabytes(static_cast<double>(report_.bytes)) +
                     ", is too small for " + std::to_string(num_points) +
                     " points: at least " + megabytes(needed) + " (--max-memory)");
  report_.vertices =
      static_cast<std::size_t>((static_cast<double>(report_.bytes) - fixed) / kBytesPerVertex);
  if (in_proportion) {
    report_.input_vertices = static_cast<std::size_t>(
        (kTrianglesPerPoint * static_cast<double>(num_points) + kMinTriangles) /
        kTrianglesPerVertex);
    if (report_.input_vertices < report_.vertices) {
      report_.vertices = report_.input_vertices;
      report_.limited_by_input = true;
    }
  }
}

bool VertexBudget::fit(std::shared_ptr<const SizingField>& sizing, const IsofacetAreaStats& stats) {
  if (stats.count < kMinFacetsToPredict) return false;
  const double demand = kVerticesPerTargetFacet * stats.count * stats.mean_ratio;
  report_.predicted_vertices = std::max(report_.predicted_vertices,
                                        static_cast<std::size_t>(demand * report_.coarsening));
  if (demand <= static_cast<double>(report_.vertices)) return false;
  const double factor = demand / static_cast<double>(report_.vertices);
  report_.coarsening *= factor;
  sizing = scaled_sizing(std::move(sizing), factor);
  return true;
}

bool VertexBudget::allows_refining(std::size_t vertices) {
  if (static_cast<double>(vertices) < kRefineBelow * static_cast<double>(report_.vertices))
    return true;
  report_.refinement_stopped = true;
  return false;
}

}  // namespace detail

std::size_t parse_memory_size(const std::string& text, const std::string& what) {
  const auto bad = [&](const std::string& why) {
    return InputError(what + ": " + quote(text) + " is not a memory size (" + why +
                      "; e.g. 8G, 500M, 1.5GiB)");
  };
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) throw bad("no number");
  std::string unit(end);
  unit.erase(std::remove_if(unit.begin(), unit.end(), [](unsigned char c) { return std::isspace(c); }),
             unit.end());
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  static const std::vector<std::pair<std::vector<std::string>, double>> units = {
      {{"", "B"}, 1},
      {{"K", "KB", "KIB"}, 1024.0},
      {{"M", "MB", "MIB"}, 1024.0 * 1024},
      {{"G", "GB", "GIB"}, 1024.0 * 1024 * 1024},
      {{"T", "TB", "TIB"}, 1024.0 * 1024 * 1024 * 1024}};
  for (const auto& [names, scale] : units)
    if (std::find(names.begin(), names.end(), unit) != names.end()) {
      const double bytes = value * scale;
      if (!std::isfinite(bytes) || bytes < 1) throw bad("it must be positive");
      if (bytes > 9.2e18) throw bad("too large");
      return static_cast<std::size_t>(bytes);
    }
  throw bad("unknown unit " + quote(end));
}

}  // namespace pdd
