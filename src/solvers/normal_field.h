// Private to src/solvers: the smoothed normal field n~ of the screened
// Poisson solver (Eq. (13)).
#pragma once

#include <pdd/types.h>

#include "common/nearest_neighbors.h"

#include <vector>

namespace pdd::detail {

// The functions below take the samples' tree (built once per solve, its
// queries read-only and concurrent) beside the samples.

// Mean distance from a sample to its nearest other sample.
double mean_spacing(const std::vector<Vec3>& points, const NearestNeighbors& tree);

// n~, constant in each tet: the average over tet t of
//   n~(x) = sum_p K_sigma(x - p) n_p,
// K_sigma the unit-mass Gaussian of standard deviation sigma. In a tet no
// larger than the kernel, by the tet's four-point rule, each point's
// Gaussian widened by the variance of a quarter of the tet; in a larger one,
// by one Gaussian at the centroid widened by the tet's whole variance (the
// uniform distribution's). Exact in the first two moments, it keeps every
// normal's contribution when tets are coarser than the kernel (no aliasing).
// The kernel is cut at 3 standard deviations.
std::vector<Vec3> smoothed_normal_field(const TetMesh& mesh, const std::vector<Vec3>& points,
                                        const NearestNeighbors& tree,
                                        const std::vector<Vec3>& normals, double sigma);

// Per sample, the mean of the samples' Gaussian density estimates (kernel
// sigma) over the sample's own: weighting each normal by it gives every part
// of the surface the same normal mass however unevenly it was sampled, as
// PoissonRecon weights its samples [KH13].
std::vector<double> density_weights(const std::vector<Vec3>& points, const NearestNeighbors& tree,
                                    double sigma);

}  // namespace pdd::detail
