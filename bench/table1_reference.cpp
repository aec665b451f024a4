// The reference isosurface of Table 1 (§4.2), built as the paper describes:
//   (1) SSD on a dense octree-based domain; (2) sample its isosurface densely
//   and offset the samples along the negative and positive normals; (3) insert
//   both layers into a Delaunay triangulation (Domain::initial, §3.2); (4)
//   optimize it with the ASAP energy; (5) solve with SSD and contour.
// Used by bench/table1.sh, which compares the four domain strategies of
// `pdd reconstruct --domain` against it.
//
//   table1_reference spacing INPUT
//       prints the input's average spacing
//   table1_reference default-edge INPUT
//       prints pdd's default target edge (pdd::default_target_edge)
//   table1_reference build INPUT OUTPUT.ply STATS.json --edge H
//                    [--octree-depth D] [--asap-rounds R] [--seed S]
//       builds the reference (below)
//   table1_reference crop MESH INPUT RADIUS OUTPUT.ply
//       keeps the faces of MESH whose centroid lies within RADIUS of an input
//       point: the scanned part of a surface reconstructed from a partial scan,
//       where the distances between reconstructions mean something
//
// H: the spacing of the samples of step (2), one layer at -H/2 and one at
// +H/2 along the normal, each of area / (sqrt(3)/2 H^2) samples (a
// triangular lattice of edge H). D: the depth of the octree of step (1);
// default: one more than `pdd reconstruct --domain octree` uses. R: ASAP rounds of
// step (4), default 0: on this two-layer domain, whose far field is the
// coarse initial domain, one round of pdd::optimize_domain (ASAP, damping,
// no mid-edge) moves vertices by up to 30 % of the domain's diameter and the
// isosurface of step (5) leaves the layers (kitten: 63.6k isovertices and
// 99.6 % of the vertices around them without the round, 8.2k and 15 % with
// it; docs/benchmarks.md, "Table 1"). The solver is SSD with the defaults of
// solvers.h, as `pdd reconstruct` uses them. STATS.json has the fields of
// `pdd reconstruct --stats` that Table 1 reads (the last entry of
// "iterations") and the sizes and times of each step.
// Exit codes: 0 done, 1 a step failed, 2 bad usage.
#include <pdd/compare.h>
#include <pdd/contour.h>
#include <pdd/errors.h>
#include <pdd/io.h>
#include <pdd/optimize.h>
#include <pdd/pipeline.h>
#include <pdd/sizing.h>
#include <pdd/solvers.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

using namespace pdd;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Options {
  std::string input, output, stats;
  double edge = 0;       // H
  int octree_depth = 0;  // 0: one deeper than the octree strategy
  int asap_rounds = 0;   // step (4), see the header
  unsigned long seed = 0;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "table1_reference: " << why << "\n"
            << "usage: table1_reference spacing INPUT\n"
            << "       table1_reference default-edge INPUT\n"
            << "       table1_reference crop MESH INPUT RADIUS OUTPUT.ply\n"
            << "       table1_reference build INPUT OUTPUT.ply STATS.json --edge H"
               " [--octree-depth D] [--asap-rounds R] [--seed S]\n";
  std::exit(2);
}

// Area-uniform samples of `mesh` pushed by `offset` along their face's unit
// normal. Written here rather than with pdd::sample_surface because the
// offset needs the face each sample lies on.
std::vector<Vec3> offset_samples(const TriangleMesh& mesh, std::size_t count, double offset,
                                 std::mt19937_64& rng) {
  std::vector<double> areas(mesh.faces.size());
  std::vector<Vec3> normals(mesh.faces.size(), Vec3::Zero());
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    const auto& f = mesh.faces[i];
    const Vec3 n = (mesh.vertices[f[1]] - mesh.vertices[f[0]])
                       .cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    areas[i] = n.norm() / 2;
    if (areas[i] > 0) normals[i] = n.normalized();
  }
  std::discrete_distribution<std::size_t> face(areas.begin(), areas.end());
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Vec3> samples;
  samples.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = face(rng);
    const auto& f = mesh.faces[i];
    const double r = std::sqrt(unit(rng)), s = unit(rng);  // uniform in the triangle
    const Vec3 p = (1 - r) * mesh.vertices[f[0]] + r * (1 - s) * mesh.vertices[f[1]] +
                   r * s * mesh.vertices[f[2]];
    samples.push_back(p + offset * normals[i]);
  }
  return samples;
}

// The faces of `mesh` whose centroid is within `radius` of a point of
// `points`, with the vertices they use. A hash grid of cell `radius` finds the
// candidates: CGAL stays in src/ and the library's kd-tree is private to it.
TriangleMesh crop(const TriangleMesh& mesh, const std::vector<Vec3>& points, double radius) {
  auto cell = [radius](const Vec3& p) {
    return Eigen::Vector3i((p / radius).array().floor().cast<int>());
  };
  auto key = [](const Eigen::Vector3i& c) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x()) & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.y()) & 0x1fffff) << 21) |
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.z()) & 0x1fffff));
  };
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  for (std::size_t i = 0; i < points.size(); ++i)
    grid[key(cell(points[i]))].push_back(static_cast<int>(i));
  auto near = [&](const Vec3& p) {
    const Eigen::Vector3i c = cell(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = grid.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (found == grid.end()) continue;
          for (int i : found->second)
            if ((points[i] - p).squaredNorm() <= radius * radius) return true;
        }
    return false;
  };
  TriangleMesh kept;
  std::vector<int> index(mesh.vertices.size(), -1);
  for (const auto& f : mesh.faces) {
    if (!near((mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3)) continue;
    std::array<int, 3> face{};
    for (int k = 0; k < 3; ++k) {
      if (index[f[k]] < 0) {
        index[f[k]] = static_cast<int>(kept.vertices.size());
        kept.vertices.push_back(mesh.vertices[f[k]]);
      }
      face[k] = index[f[k]];
    }
    kept.faces.push_back(face);
  }
  return kept;
}

int build(const Options& o) {
  const auto start = Clock::now();
  const PointSet points = read_points(o.input);

  // (1) SSD on the octree-based domain (§4.2, strategy 1), one level deeper
  // than `pdd reconstruct --domain octree`.
  ReconstructOptions seed_options;
  seed_options.strategy = DomainStrategy::kOctree;
  seed_options.octree_depth = o.octree_depth > 0 ? o.octree_depth : 1 + default_octree_depth(points);
  const Result seed = reconstruct(points, seed_options);
  const double seconds_seed = seconds_since(start);

  // (2) two offset layers, (3) inserted into the initial domain of §3.2, f
  // carried over from step (1) (both domains share the hull of Domain::initial).
  auto t = Clock::now();
  const double area = surface_area(seed.mesh);
  const auto per_layer =
      static_cast<std::size_t>(std::ceil(area / (std::sqrt(3.0) / 2 * o.edge * o.edge)));
  std::mt19937_64 rng(o.seed);
  Domain domain = Domain::initial(points);
  std::vector<Vec3> layers;
  for (double side : {-0.5, 0.5})
    for (const Vec3& p : offset_samples(seed.mesh, per_layer, side * o.edge, rng))
      if (domain.locate(p).tet >= 0) layers.push_back(p);
  domain.insert(layers);
  std::vector<double> f(domain.num_vertices());
  for (std::size_t v = 0; v < f.size(); ++v)
    f[v] = seed.domain.interpolate(domain.vertices()[v], seed.domain.f());
  domain.set_f(std::move(f));
  const double seconds_sandwich = seconds_since(t);

  // (4) ASAP rounds (no mid-edge term: there is no isosurface to fit yet).
  t = Clock::now();
  OptimizerOptions asap;
  asap.mid_edge = false;
  for (int round = 0; round < o.asap_rounds; ++round) optimize_domain(domain, asap);
  const double seconds_optimize = seconds_since(t);

  // (5) SSD and marching tetrahedra.
  t = Clock::now();
  // CHOLMOD: one solve on a domain not refined from earlier ones, so no
  // coarse levels for the multigrid to reuse.
  SolverOptions direct;
  direct.linear.method = LinearMethod::kCholmod;
  const auto solver = make_solver(direct);
  const std::vector<double> warm = domain.f();
  domain.set_f(solver->solve(domain, points, &warm));
  const double seconds_solve = seconds_since(t);
  const IsoSurface iso = marching_tetrahedra(domain.mesh(), domain.f());
  write_mesh(o.output, iso.mesh);

  // Table 1's columns, counted as pdd reconstruct counts them.
  std::vector<char> near(domain.num_vertices(), 0);
  for (int tet : iso.facet_tet)
    for (int v : domain.tets()[tet]) near[v] = 1;
  const auto near_count = static_cast<std::size_t>(std::count(near.begin(), near.end(), 1));
  const double seconds = seconds_since(start);
  std::ofstream json(o.stats);
  json.precision(10);
  json << "{\n  \"strategy\": \"reference\",\n  \"solver\": \"ssd\",\n"
       << "  \"seconds\": " << seconds << ",\n"
       << "  \"vertices\": " << domain.num_vertices() << ",\n"
       << "  \"triangles\": " << iso.mesh.faces.size() << ",\n"
       << "  \"isovertices\": " << iso.mesh.vertices.size() << ",\n"
       << "  \"edge\": " << o.edge << ",\n"
       << "  \"octree_depth\": " << seed_options.octree_depth << ",\n"
       << "  \"octree_vertices\": " << seed.domain.num_vertices() << ",\n"
       << "  \"samples_per_layer\": " << per_layer << ",\n"
       << "  \"asap_rounds\": " << o.asap_rounds << ",\n"
       << "  \"seconds_steps\": {\"octree\": " << seconds_seed
       << ", \"layers\": " << seconds_sandwich << ", \"optimize\": " << seconds_optimize
       << ", \"solve\": " << seconds_solve << "},\n"
       << "  \"iterations\": [{\"iteration\": 1, \"final\": true, \"vertices\": "
       << domain.num_vertices() << ", \"vertices_near_isosurface\": " << near_count
       << ", \"parsimony\": "
       << static_cast<double>(near_count) / static_cast<double>(domain.num_vertices())
       << ", \"isovertices\": " << iso.mesh.vertices.size()
       << ", \"triangles\": " << iso.mesh.faces.size() << "}]\n}\n";
  if (!json) throw InputError(o.stats + ": cannot write");
  std::fprintf(stderr,
               "table1_reference: octree depth %d (%zu vertices), 2 x %zu samples, %zu vertices, "
               "%zu isovertices, parsimony %.3f, %.1f s\n",
               seed_options.octree_depth, seed.domain.num_vertices(), per_layer,
               domain.num_vertices(), iso.mesh.vertices.size(),
               static_cast<double>(near_count) / static_cast<double>(domain.num_vertices()),
               seconds);
  return 0;
}

// The value of a flag: a finite number, > 0 or (zero_ok) >= 0.
double number(const std::string& flag, const std::string& text, bool zero_ok = false) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value) && (value > 0 || (zero_ok && value == 0)))
      return value;
  } catch (const std::exception&) {
  }
  usage(flag + " wants a " + (zero_ok ? "non-negative" : "positive") + " number, got '" + text +
        "'");
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 2 && args[0] == "spacing") {
      std::printf("%.10g\n", average_spacing(read_points(args[1])));
      return 0;
    }
    if (args.size() == 2 && args[0] == "default-edge") {
      std::printf("%.10g\n", default_target_edge(read_points(args[1])));
      return 0;
    }
    if (args.size() == 5 && args[0] == "crop") {
      const TriangleMesh kept =
          crop(read_mesh(args[1]), read_points(args[2]).points, number("RADIUS", args[3]));
      if (kept.faces.empty())
        throw InputError(args[1] + ": no face within " + args[3] + " of the input");
      write_mesh(args[4], kept);
      return 0;
    }
    if (args.size() < 4 || args[0] != "build")
      usage(
          "expected 'spacing INPUT', 'default-edge INPUT', 'build INPUT OUTPUT STATS --edge H' or 'crop MESH INPUT "
          "RADIUS OUTPUT'");
    Options o;
    o.input = args[1];
    o.output = args[2];
    o.stats = args[3];
    for (std::size_t i = 4; i < args.size(); i += 2) {
      if (i + 1 >= args.size()) usage(args[i] + " needs a value");
      const std::string& value = args[i + 1];
      if (args[i] == "--edge")
        o.edge = number(args[i], value);
      else if (args[i] == "--octree-depth")
        o.octree_depth = static_cast<int>(number(args[i], value));
      else if (args[i] == "--asap-rounds")
        o.asap_rounds = static_cast<int>(number(args[i], value, true));
      else if (args[i] == "--seed")
        o.seed = static_cast<unsigned long>(number(args[i], value, true));
      else
        usage("unknown option " + args[i]);
    }
    if (o.edge <= 0) usage("--edge is required");
    return build(o);
  } catch (const std::exception& e) {
    std::cerr << "table1_reference: " << e.what() << "\n";
    return 1;
  }
}
