// A sequential CGAL triangulation from the domain's arrays, with no
// predicate: a cell per tet (its corners in the same order, its info the
// tet's index) and across each hull face an infinite cell, as CGAL orients
// them.
#include "domain/concurrent_delaunay.h"

#include <map>
#include <stdexcept>
#include <utility>

namespace pdd::detail {

void triangulation_from_arrays(const TetMesh& mesh,
                               const std::vector<std::array<int, 4>>& neighbors,
                               const std::vector<int>& vertex_cells, Delaunay& dt,
                               std::vector<Delaunay::Vertex_handle>& handles,
                               std::vector<Delaunay::Cell_handle>& cells) {
  const std::vector<std::array<int, 4>>& tets = mesh.tets;
  detail::Tds& tds = dt.tds();
  tds.clear();
  const Delaunay::Vertex_handle infinite = tds.create_vertex();
  dt.set_infinite_vertex(infinite);
  tds.set_dimension(3);
  handles.resize(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    handles[i] = tds.create_vertex();
    handles[i]->set_point(to_point(mesh.vertices[i]));
    handles[i]->info() = static_cast<int>(i);
  }
  cells.resize(tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& k = tets[t];
    cells[t] = tds.create_cell(handles[k[0]], handles[k[1]], handles[k[2]], handles[k[3]]);
    cells[t]->info() = static_cast<int>(t);
  }
  // An infinite cell is its finite neighbour with the infinite vertex in
  // place of the far corner and two corners swapped (opposite orientation);
  // infinite cells meet across the faces through a hull edge and infinity.
  std::map<std::pair<int, int>, std::pair<Delaunay::Cell_handle, int>> open_edges;
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int i = 0; i < 4; ++i) {
      const int across = neighbors[t][i];
      if (across >= 0) {
        cells[t]->set_neighbor(i, cells[across]);
        continue;
      }
      std::array<Delaunay::Vertex_handle, 4> v{handles[tets[t][0]], handles[tets[t][1]],
                                               handles[tets[t][2]], handles[tets[t][3]]};
      v[i] = infinite;
      std::swap(v[(i + 1) % 4], v[(i + 2) % 4]);
      const Delaunay::Cell_handle c = tds.create_cell(v[0], v[1], v[2], v[3]);
      c->info() = -1;
      c->set_neighbor(i, cells[t]);
      cells[t]->set_neighbor(i, c);
      for (int m = 0; m < 4; ++m) {
        if (m == i) continue;
        int a = -1, b = -1;
        for (int e = 0; e < 4; ++e)
          if (e != i && e != m) (a < 0 ? a : b) = v[e]->info();
        const auto key = std::minmax(a, b);
        const auto found = open_edges.find(key);
        if (found == open_edges.end()) {
          open_edges.emplace(key, std::make_pair(c, m));
        } else {
          c->set_neighbor(m, found->second.first);
          found->second.first->set_neighbor(found->second.second, c);
          open_edges.erase(found);
        }
      }
    }
  if (!open_edges.empty())
    throw std::logic_error("Domain: the hull of the tets is not closed: no triangulation");
  auto decode = [&](int code) {
    return code >= 0 ? cells[code] : cells[(-2 - code) / 4]->neighbor((-2 - code) % 4);
  };
  for (std::size_t i = 0; i < handles.size(); ++i)
    handles[i]->set_cell(decode(vertex_cells[i]));
  infinite->set_cell(decode(vertex_cells.back()));
}

}  // namespace pdd::detail
