// Where the input points fall in the domain: point location, the sampling
// matrix Phi (Eq. (14)) and the selection matrix S (Eq. (15)).
#include <pdd/errors.h>
#include <pdd/fem.h>

#include "common/cancellation.h"
#include "domain/triangulation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <sstream>
#include <stdexcept>

namespace pdd {

std::vector<std::size_t> location_order(const std::vector<Vec3>& points) {
  std::vector<detail::Point> cgal_points;
  cgal_points.reserve(points.size());
  for (const Vec3& p : points) cgal_points.push_back(detail::to_point(p));
  return detail::spatial_order(cgal_points);
}

std::vector<Location> locate_points(const Domain& domain, const std::vector<Vec3>& points,
                                    const std::vector<std::size_t>* given_order) {
  const int n = static_cast<int>(points.size());
  std::vector<Location> locations(n);
  // In spatial order, each point located from the tet of the one before it:
  // a walk of a few steps instead of one across the domain. Blocks of a fixed
  // size start afresh, so that the locations do not depend on the thread
  // count; Domain::locate only reads the triangulation (CGAL's walk keeps its
  // random state local), so blocks run concurrently.
  std::vector<std::size_t> own_order;
  if (!given_order) own_order = location_order(points);
  const std::vector<std::size_t>& order = given_order ? *given_order : own_order;
  if (order.size() != points.size())
    throw std::invalid_argument("locate_points: the order has " + std::to_string(order.size()) +
                                " entries for " + std::to_string(points.size()) + " points");
  constexpr int kBlock = 256;
  detail::polled_parallel_for(
      (n + kBlock - 1) / kBlock,
      [&](int b) {
        const Location* near = nullptr;
        for (int k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
          const std::size_t i = order[k];
          locations[i] = near ? domain.locate(points[i], *near) : domain.locate(points[i]);
          if (locations[i].tet >= 0) near = &locations[i];
        }
      },
      128);
  int outside = 0, first = -1;
  for (int i = 0; i < n; ++i)
    if (locations[i].tet < 0) {
      if (first < 0) first = i;
      ++outside;
    }
  if (outside > 0) {
    std::ostringstream msg;
    msg << outside << " of " << n << " points lie outside the domain (first: point " << first + 1
        << " at " << points[first].x() << " " << points[first].y() << " " << points[first].z()
        << ")";
    throw InputError(msg.str());
  }
  return locations;
}

SparseMatrix sampling_matrix(const TetMesh& mesh, const std::vector<Location>& locations) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(4 * locations.size());
  for (std::size_t p = 0; p < locations.size(); ++p) {
    const Location& loc = locations[p];
    if (loc.tet < 0 || loc.tet >= static_cast<int>(mesh.tets.size()))
      throw std::invalid_argument("sampling_matrix: point " + std::to_string(p + 1) +
                                  " is not located in the mesh");
    for (int i = 0; i < 4; ++i)
      entries.emplace_back(static_cast<int>(p), mesh.tets[loc.tet][i], loc.barycentric[i]);
  }
  SparseMatrix Phi(static_cast<Eigen::Index>(locations.size()),
                   static_cast<Eigen::Index>(mesh.vertices.size()));
  Phi.setFromTriplets(entries.begin(), entries.end());
  return Phi;
}

SparseMatrix selection_matrix(std::size_t num_tets, const std::vector<Location>& locations) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * locations.size());
  for (std::size_t p = 0; p < locations.size(); ++p) {
    const int t = locations[p].tet;
    if (t < 0 || t >= static_cast<int>(num_tets))
      throw std::invalid_argument("selection_matrix: point " + std::to_string(p + 1) +
                                  " is not located in the mesh");
    for (int k = 0; k < 3; ++k) entries.emplace_back(static_cast<int>(3 * p + k), 3 * t + k, 1.0);
  }
  SparseMatrix S(3 * static_cast<Eigen::Index>(locations.size()),
                 3 * static_cast<Eigen::Index>(num_tets));
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

}  // namespace pdd
