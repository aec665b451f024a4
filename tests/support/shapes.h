// Generated analytic shapes for the tests: points with exact normals sampled
// on a sphere, an ellipsoid and a torus, plus their exact distance functions.
#pragma once

#include <pdd/types.h>

namespace pdd::test {

// n points spread evenly (Fibonacci lattice) on the sphere (center, radius).
PointSet sample_sphere(int n, double radius = 1.0, const Vec3& center = Vec3::Zero());
// n points on the ellipsoid with semi-axes (a, b, c), normals exact.
PointSet sample_ellipsoid(int n, const Vec3& axes);
// About n points on the torus around the z axis (major radius R, minor r).
PointSet sample_torus(int n, double R, double r);

// Distance from p to the ellipsoid surface (numerical, accurate to 1e-10).
double distance_to_ellipsoid(const Vec3& p, const Vec3& axes);
// Distance from p to the torus surface.
double distance_to_torus(const Vec3& p, double R, double r);

// A closed triangle mesh of the sphere: an octahedron whose faces are split
// into 4^levels triangles, projected onto the sphere; outward-facing.
TriangleMesh sphere_mesh(int levels, double radius = 1.0);

// Adds Gaussian noise of standard deviation sigma to the positions.
void add_noise(PointSet& points, double sigma, unsigned seed);

}  // namespace pdd::test
