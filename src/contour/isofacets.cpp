#include <pdd/isofacet.h>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "common/cancellation.h"

namespace pdd {
namespace {

// Gradient of the linear interpolant of f over a tet: solves
// [v1-v0; v2-v0; v3-v0] g = [f1-f0; f2-f0; f3-f0].
Vec3 tet_gradient(const std::array<Vec3, 4>& v, const std::array<double, 4>& f) {
  Eigen::Matrix3d E;
  E.row(0) = (v[1] - v[0]).transpose();
  E.row(1) = (v[2] - v[0]).transpose();
  E.row(2) = (v[3] - v[0]).transpose();
  return E.partialPivLu().solve(Vec3(f[1] - f[0], f[2] - f[0], f[3] - f[0]));
}

}  // namespace

double Isofacet::largest_triangle_area() const {
  if (num_corners != 4) return area;
  const auto half = [&](int a, int b, int c) {
    return 0.5 * (corners[b] - corners[a]).cross(corners[c] - corners[a]).norm();
  };
  if ((corners[0] - corners[2]).squaredNorm() <= (corners[1] - corners[3]).squaredNorm())
    return std::max(half(0, 1, 2), half(0, 2, 3));
  return std::max(half(0, 1, 3), half(1, 2, 3));
}

bool crosses_isovalue(const TetMesh& mesh, const std::vector<double>& f, int t, double isovalue) {
  int negative = 0;
  for (int v : mesh.tets[t]) negative += f[v] < isovalue;
  return negative > 0 && negative < 4;
}

bool isofacet(const TetMesh& mesh, const std::vector<double>& f, int t, Isofacet& a,
              double isovalue) {
  const auto& tet = mesh.tets[t];
  int neg[4], pos[4], nn = 0, np = 0;
  for (int i = 0; i < 4; ++i) (f[tet[i]] < isovalue ? neg[nn++] : pos[np++]) = tet[i];
  if (nn == 0 || np == 0) return false;

  a = Isofacet();
  a.tet = t;
  a.negative_vertices = nn;
  // Crossing edges in cyclic order around the facet.
  std::array<std::array<int, 2>, 4> cycle;
  if (nn == 1) {
    cycle = {{{neg[0], pos[0]}, {neg[0], pos[1]}, {neg[0], pos[2]}, {0, 0}}};
  } else if (np == 1) {
    cycle = {{{neg[0], pos[0]}, {neg[1], pos[0]}, {neg[2], pos[0]}, {0, 0}}};
  } else {
    cycle = {{{neg[0], pos[0]}, {neg[0], pos[1]}, {neg[1], pos[1]}, {neg[1], pos[0]}}};
  }
  a.num_corners = (nn == 2) ? 4 : 3;
  for (int k = 0; k < a.num_corners; ++k) {
    const int i = cycle[k][0], j = cycle[k][1];
    const double s = (isovalue - f[i]) / (f[j] - f[i]);
    a.corners[k] = mesh.vertices[i] + s * (mesh.vertices[j] - mesh.vertices[i]);
    a.edges[k] = {std::min(i, j), std::max(i, j)};
  }
  // Area and centroid from the fan (0,1,2), (0,2,3).
  for (int k = 1; k + 1 < a.num_corners; ++k) {
    const double area =
        0.5 * (a.corners[k] - a.corners[0]).cross(a.corners[k + 1] - a.corners[0]).norm();
    a.area += area;
    a.centroid += area * (a.corners[0] + a.corners[k] + a.corners[k + 1]) / 3.0;
  }
  if (a.area > 0) {
    a.centroid /= a.area;
  } else {
    for (int k = 0; k < a.num_corners; ++k) a.centroid += a.corners[k] / a.num_corners;
  }
  const std::array<Vec3, 4> v{mesh.vertices[tet[0]], mesh.vertices[tet[1]],
                              mesh.vertices[tet[2]], mesh.vertices[tet[3]]};
  a.normal = tet_gradient(v, {f[tet[0]], f[tet[1]], f[tet[2]], f[tet[3]]}).normalized();
  return true;
}

std::vector<Isofacet> isofacets(const TetMesh& mesh, const std::vector<double>& f,
                                double isovalue) {
  // Blocks of tets in parallel, each writing its facets after those of the
  // blocks before it: tet order, whatever the thread count. The facets are
  // counted first and written in place (grown per block and then gathered,
  // they took three times the output's memory at the peak).
  constexpr int kBlock = 8192;
  const int m = static_cast<int>(mesh.tets.size());
  const int blocks = (m + kBlock - 1) / kBlock;
  std::vector<std::size_t> offset(blocks + 1, 0);
  detail::polled_parallel_for(
      blocks,
      [&](int k) {
        for (int t = k * kBlock; t < std::min(m, (k + 1) * kBlock); ++t)
          offset[k + 1] += crosses_isovalue(mesh, f, t, isovalue);
      },
      4);
  for (int k = 0; k < blocks; ++k) offset[k + 1] += offset[k];
  std::vector<Isofacet> out(offset[blocks]);
  detail::polled_parallel_for(
      blocks,
      [&](int k) {
        std::size_t next = offset[k];
        for (int t = k * kBlock; t < std::min(m, (k + 1) * kBlock); ++t)
          if (crosses_isovalue(mesh, f, t, isovalue)) isofacet(mesh, f, t, out[next++], isovalue);
      },
      4);
  return out;
}

}  // namespace pdd
