#include "support/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace pdd::test {
namespace {

// Unit direction i of n on the Fibonacci lattice.
Vec3 fibonacci_direction(int i, int n) {
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(rho * std::cos(golden_angle * i), rho * std::sin(golden_angle * i), z);
}

}  // namespace

PointSet sample_sphere(int n, double radius, const Vec3& center) {
  PointSet ps;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = fibonacci_direction(i, n);
    ps.points.push_back(center + radius * d);
    ps.normals.push_back(d);
  }
  return ps;
}

PointSet sample_ellipsoid(int n, const Vec3& axes) {
  PointSet ps;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = fibonacci_direction(i, n);
    const Vec3 p = d.cwiseProduct(axes);
    ps.points.push_back(p);
    ps.normals.push_back(p.cwiseQuotient(axes.cwiseProduct(axes)).normalized());
  }
  return ps;
}

PointSet sample_torus(int n, double R, double r) {
  // A grid in (u, v) whose spacing is even in arc length along the major circle.
  const int nu = std::max(3, static_cast<int>(std::round(std::sqrt(n * R / r))));
  const int nv = std::max(3, n / nu);
  PointSet ps;
  for (int i = 0; i < nu; ++i) {
    const double u = 2 * M_PI * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2 * M_PI * (j + 0.5 * (i % 2)) / nv;
      const Vec3 radial(std::cos(u), std::sin(u), 0);
      const Vec3 normal = std::cos(v) * radial + Vec3(0, 0, std::sin(v));
      ps.points.push_back(R * radial + r * normal);
      ps.normals.push_back(normal);
    }
  }
  return ps;
}

double distance_to_torus(const Vec3& p, double R, double r) {
  const double q = std::hypot(p.x(), p.y()) - R;
  return std::abs(std::hypot(q, p.z()) - r);
}

double distance_to_ellipsoid(const Vec3& p, const Vec3& axes) {
  // Closest point by Newton on the Lagrange parameter t: x_i = a_i^2 p_i / (a_i^2 + t).
  const Vec3 a2 = axes.cwiseProduct(axes);
  double t = 0;
  for (int it = 0; it < 200; ++it) {
    double g = -1, dg = 0;
    for (int i = 0; i < 3; ++i) {
      const double s = axes[i] * p[i] / (a2[i] + t);
      g += s * s;
      dg += -2 * s * s / (a2[i] + t);
    }
    const double step = g / dg;
    double next = t - step;
    const double lower = -a2.minCoeff();
    if (next <= lower) next = 0.5 * (t + lower);
    if (std::abs(next - t) < 1e-14 * (1 + std::abs(t))) break;
    t = next;
  }
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = a2[i] * p[i] / (a2[i] + t);
  return (p - x).norm();
}

void add_noise(PointSet& points, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  for (Vec3& p : points.points) p += Vec3(g(rng), g(rng), g(rng));
}

TriangleMesh sphere_mesh(int levels, double radius) {
  TriangleMesh mesh;
  mesh.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0),
                   Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  mesh.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      mesh.vertices.push_back((mesh.vertices[a] + mesh.vertices[b]).normalized());
      const int id = static_cast<int>(mesh.vertices.size()) - 1;
      middle.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> faces;
    for (const auto& f : mesh.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({ab, f[1], bc});
      faces.push_back({ca, bc, f[2]});
      faces.push_back({ab, bc, ca});
    }
    mesh.faces = std::move(faces);
  }
  for (Vec3& v : mesh.vertices) v *= radius;
  return mesh;
}

}  // namespace pdd::test
