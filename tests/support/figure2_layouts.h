// The four discretizations of the paper's Figure 2 (§2.2): two concentric
// layers of vertices around the unit sphere, Delaunay-triangulated, carrying
// the analytic f(x) = |x| - 1. Shared by tests/contour_test.cpp and
// bench/figure2.cpp (which compiles this file in).
#pragma once

#include <pdd/domain.h>

namespace pdd::test {

enum class Figure2Layout {
  kBiasedRandom,    // (a) random directions, layers at radii 0.95 and 1.15
  kUnbiasedRandom,  // (b) random directions, layers at radii 0.9 and 1.1
  kBiasedEven,      // (c) evenly-placed directions, layers at 0.95 and 1.15
  kUnbiasedEven,    // (d) evenly-placed directions, layers at 0.9 and 1.1
  // (d) with the outer layer on the inner layer's directions instead of
  // staggered; kept to show why (d) staggers them (docs/benchmarks.md).
  kUnbiasedEvenAligned,
};

// "(a) biased random" etc.
const char* figure2_label(Figure2Layout layout);

// The domain of one layout with f = |x| - 1 at its vertices, points_per_layer
// vertices on each layer.
// - Random layers: each layer draws its own directions, uniform on the sphere
//   (normalized Gaussian vectors from std::mt19937(seed) for the inner layer,
//   seed + 1 for the outer).
// - Evenly-placed layers: the inner layer on the Fibonacci lattice, the outer
//   on the same lattice turned about its axis by half the golden angle, so
//   that outer vertices sit between inner ones (staggered, like the two
//   layers of a body-centred lattice) and the tets between the layers are
//   well shaped. On the very same directions (kUnbiasedEvenAligned) every
//   quadrilateral a_i a_j b_j b_i is planar and cocircular; once 0.9 u and
//   1.1 u are rounded to doubles the Delaunay triangulation keeps some of
//   them as flat slivers, whose isofacets collapse to segments.
// Unbiased layers sit at 1 -+ 0.1, so every edge from the inner to the outer
// layer is crossed by the linear interpolant of f at its midpoint (t = 1/2);
// biased layers (0.95, 1.15) are crossed at t = 1/4 from the inner end.
Domain figure2_domain(Figure2Layout layout, int points_per_layer, unsigned seed = 1);

}  // namespace pdd::test
