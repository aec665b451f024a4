// The run's first step when the input's normals are missing or untrusted:
// estimate them and orient them (pipeline.h, NormalsMode and Orientation).
#pragma once

#include <pdd/pipeline.h>

namespace pdd::detail {

// `points` itself when its normals are used as given; otherwise `storage`,
// filled with the points and their new normals. `report` says what was done.
// Throws Cancelled (common/cancellation.h) when the progress callback stops
// the orientation's coarse run.
const PointSet& prepare_normals(const PointSet& points, const ReconstructOptions& options,
                                PointSet& storage, NormalsReport& report);

}  // namespace pdd::detail
