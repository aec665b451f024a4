// Connected components of a triangle mesh and their removal, private to the
// contour stage (small, open and unsupported components; the trim's islands).
#pragma once

#include <pdd/contour.h>

#include <Eigen/Geometry>

#include <vector>

namespace pdd::detail {

// The connected components of a mesh (through shared vertices): a root
// vertex per vertex, and per root its number of faces.
struct Components {
  std::vector<int> root_of;  // per vertex
  std::vector<int> faces;    // per root vertex; 0 for the others
  int largest = -1;          // the root with the most faces (the first such)
};
Components components(const TriangleMesh& mesh);

// Per root vertex, the bounding box of its component's faces (empty for the others).
std::vector<Eigen::AlignedBox3d> component_boxes(const TriangleMesh& mesh, const Components& c);

// Drops the faces of the components whose root is marked, and the vertices
// they leave unused; the others keep their order. Counts what went.
RemovedComponents remove_marked(TriangleMesh& mesh, const Components& c,
                                const std::vector<char>& marked);

// Drops the vertices no face uses; the others keep their order.
void drop_unused_vertices(TriangleMesh& mesh);

}  // namespace pdd::detail
