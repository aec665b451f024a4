// The trim's rim remeshed for the mesh's quality, private to the contour stage.
#pragma once

#include <pdd/types.h>

#include <utility>
#include <vector>

namespace pdd::detail {

// Within two rings of the boundary (its edges, a < b): triangles flattened onto
// it removed, edges shorter than 0.4 `edge` collapsed, edges flipped and
// vertices moved in their tangent planes, each only where it raises the
// smallest angle of the triangles it touches.
void remesh_rim(TriangleMesh& mesh, const std::vector<std::pair<int, int>>& boundary, double edge);

}  // namespace pdd::detail
