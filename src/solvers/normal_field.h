// Private to src/solvers: the smoothed normal field n~ of the screened
// Poisson solver (Eq. (13)).
#pragma once

#include <pdd/types.h>

#include <vector>

namespace pdd::detail {

// Mean distance from a sample to its nearest other sample.
double mean_spacing(const std::vector<Vec3>& points);

// n~, constant in each tet: the average over tet t of
//   n~(x) = sum_p K_sigma(x - p) n_p,
// K_sigma the unit-mass Gaussian of standard deviation sigma. The average of a
// Gaussian over a tet is approximated by a Gaussian at the tet's centroid
// whose variance adds the tet's own (the variance of the uniform distribution
// on the tet): exact in its first two moments, and it keeps every normal's
// contribution when tets are coarser than the kernel (no aliasing). The
// kernel is cut at 3 standard deviations.
std::vector<Vec3> smoothed_normal_field(const TetMesh& mesh, const std::vector<Vec3>& points,
                                        const std::vector<Vec3>& normals, double sigma);

}  // namespace pdd::detail
