// Attributes carried from the samples to the output's vertices (contour.h).
#include <pdd/contour.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/nearest_neighbors.h"

namespace pdd {

namespace {

bool is_integer_type(const std::string& type) {
  return type != "float" && type != "double";
}

}  // namespace

std::vector<Attribute> interpolate_attributes(const PointSet& samples,
                                              const std::vector<Vec3>& vertices, int neighbors) {
  if (neighbors < 1)
    throw std::invalid_argument("interpolate_attributes: neighbors must be >= 1");
  std::vector<Attribute> out;
  if (samples.attributes.empty()) return out;
  if (samples.points.empty())
    throw std::invalid_argument("interpolate_attributes: no samples");
  for (const Attribute& a : samples.attributes) {
    if (a.values.size() != samples.size())
      throw std::invalid_argument("interpolate_attributes: attribute '" + a.name + "' has " +
                                  std::to_string(a.values.size()) + " values for " +
                                  std::to_string(samples.size()) + " points");
    out.push_back({a.name, a.type, std::vector<double>(vertices.size())});
  }
  const detail::NearestNeighbors tree(samples.points);
  tbb::parallel_for(std::size_t(0), vertices.size(), [&](std::size_t v) {
    const std::vector<int> nearest = tree.query(vertices[v], neighbors);
    // Shepard's inverse squared distance weights; a sample at the vertex itself decides alone.
    std::vector<double> weight(nearest.size());
    for (std::size_t j = 0; j < nearest.size(); ++j) {
      const double d2 = (samples.points[nearest[j]] - vertices[v]).squaredNorm();
      weight[j] = d2 > 0 ? 1 / d2 : 0;
    }
    if (weight[0] == 0) {
      std::fill(weight.begin(), weight.end(), 0.0);
      weight[0] = 1;
    }
    double total = 0;
    for (double w : weight) total += w;
    for (std::size_t a = 0; a < out.size(); ++a) {
      const Attribute& from = samples.attributes[a];
      // Labels and indices are not averaged: the nearest sample's value.
      if (is_integer_type(from.type) && !is_colour(from.name)) {
        out[a].values[v] = from.values[nearest[0]];
        continue;
      }
      double sum = 0;
      for (std::size_t j = 0; j < nearest.size(); ++j) sum += weight[j] * from.values[nearest[j]];
      out[a].values[v] = sum / total;
      if (is_integer_type(from.type)) out[a].values[v] = std::round(out[a].values[v]);
    }
  });
  return out;
}

}  // namespace pdd
