// Private to src/pipeline: the octree-based domain of §4.2 (strategy 1).
#pragma once

#include <pdd/domain.h>

namespace pdd::detail {

// Inserts into `domain` every node (cell corner) of an octree over the
// input's bounding cube, whose cells containing input points are split down
// to `depth` levels. depth <= 0: the depth whose finest cells are about the
// input's average spacing. Nodes outside the domain sphere are left out.
void insert_octree_nodes(Domain& domain, const PointSet& points, int depth);

}  // namespace pdd::detail
