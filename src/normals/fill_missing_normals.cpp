// Zero normals replaced by estimated ones (normals.h).
#include <pdd/normals.h>

#include <algorithm>
#include <stdexcept>

#include "common/nearest_neighbors.h"

namespace pdd {

std::size_t fill_missing_normals(const std::vector<Vec3>& points, std::vector<Vec3>& normals,
                                 int neighbors, const std::string& source) {
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < normals.size(); ++i)
    if (normals[i].squaredNorm() == 0) missing.push_back(i);
  if (missing.empty()) return 0;
  if (missing.size() == normals.size())
    throw std::invalid_argument("fill_missing_normals: every normal is zero (none to turn by)");
  // The jet fit runs on the missing points' neighbourhoods only (a scan with
  // a few zero normals costs a few fits), each with its own neighbours inside.
  const detail::NearestNeighbors tree(points);
  std::vector<int> subset;
  for (std::size_t i : missing)
    for (int j : tree.query(points[i], 2 * neighbors)) subset.push_back(j);
  std::sort(subset.begin(), subset.end());
  subset.erase(std::unique(subset.begin(), subset.end()), subset.end());
  std::vector<Vec3> local(subset.size());
  for (std::size_t k = 0; k < subset.size(); ++k) local[k] = points[subset[k]];
  const std::vector<Vec3> estimated = estimate_normals(
      subset.size() < kMinPointsForNormals ? points : local, neighbors, source);
  // The sign of the nearest given normals, not of the nearest points: inside
  // a patch of zero normals those give none.
  std::vector<Vec3> given_points;
  std::vector<Vec3> given_normals;
  for (std::size_t i = 0; i < normals.size(); ++i)
    if (normals[i].squaredNorm() > 0) {
      given_points.push_back(points[i]);
      given_normals.push_back(normals[i]);
    }
  const detail::NearestNeighbors given(given_points);
  std::vector<Vec3> filled(missing.size());
  for (std::size_t m = 0; m < missing.size(); ++m) {
    const std::size_t i = missing[m];
    const auto at = std::lower_bound(subset.begin(), subset.end(), static_cast<int>(i));
    Vec3 n = subset.size() < kMinPointsForNormals ? estimated[i] : estimated[at - subset.begin()];
    Vec3 around = Vec3::Zero();
    for (int j : given.query(points[i], neighbors)) around += given_normals[j];
    if (n.dot(around) < 0) n = -n;
    filled[m] = n;
  }
  for (std::size_t m = 0; m < missing.size(); ++m) normals[missing[m]] = filled[m];
  return missing.size();
}

}  // namespace pdd
