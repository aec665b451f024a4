// Surface distances (pdd/compare.h) and `pdd compare`: known offsets between
// generated meshes, asymmetric cases, the F-score's threshold, determinism,
// and the command line's exit codes and JSON.
#include <gtest/gtest.h>
#include <pdd/compare.h>
#include <pdd/errors.h>
#include <pdd/io.h>
#include <pdd/report.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <stdexcept>
#include <string>

#include "support/scratch_dir.h"

namespace pdd {
namespace {

// The unit icosphere: an icosahedron whose faces are split in four
// `levels` times, vertices pushed onto the sphere. Level 4 has 5120 faces of
// edge about 0.066.
TriangleMesh icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  for (const Vec3& v : {Vec3(-1, g, 0), Vec3(1, g, 0), Vec3(-1, -g, 0), Vec3(1, -g, 0),
                        Vec3(0, -1, g), Vec3(0, 1, g), Vec3(0, -1, -g), Vec3(0, 1, -g),
                        Vec3(g, 0, -1), Vec3(g, 0, 1), Vec3(-g, 0, -1), Vec3(-g, 0, 1)})
    m.vertices.push_back(v.normalized());
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return midpoint[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> faces;
    for (const auto& f : m.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({f[1], bc, ab});
      faces.push_back({f[2], ca, bc});
      faces.push_back({ab, bc, ca});
    }
    m.faces = faces;
  }
  return m;
}

// The smallest distance from the origin to the plane of a face (1 minus the
// flattening of an icosphere).
double nearest_face_plane(const TriangleMesh& m) {
  double h = 1e300;
  for (const auto& f : m.faces) {
    const Vec3& a = m.vertices[f[0]];
    const Vec3 n = (m.vertices[f[1]] - a).cross(m.vertices[f[2]] - a).normalized();
    h = std::min(h, std::abs(n.dot(a)));
  }
  return h;
}

TriangleMesh transformed(TriangleMesh m, double scale, const Vec3& shift = Vec3::Zero()) {
  for (Vec3& v : m.vertices) v = scale * v + shift;
  return m;
}

CompareOptions with_samples(std::size_t samples, double fscore_threshold = 0.005) {
  CompareOptions options;
  options.samples = samples;
  options.fscore_threshold = fscore_threshold;
  return options;
}

TEST(SampleSurface, SamplesLieOnTheMeshAndFollowArea) {
  // Two triangles in the plane z = 0 of areas 1/2 and 3/2.
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0), Vec3(2, 3, 0)};
  m.faces = {{0, 1, 2}, {1, 3, 4}};
  EXPECT_NEAR(surface_area(m), 2.0, 1e-12);
  const std::vector<Vec3> samples = sample_surface(m, 20000, 7);
  ASSERT_EQ(samples.size(), 20000u);
  int in_first = 0;
  for (const Vec3& p : samples) {
    EXPECT_EQ(p.z(), 0.0);
    if (p.x() + p.y() <= 1) {
      ++in_first;
      EXPECT_GE(p.x(), 0.0);
      EXPECT_GE(p.y(), 0.0);
    } else {  // inside (1,0) (2,0) (2,3)
      EXPECT_LE(p.x(), 2.0 + 1e-12);
      EXPECT_GE(p.y(), -1e-12);
      EXPECT_LE(p.y(), 3 * (p.x() - 1) + 1e-12);
    }
  }
  // Binomial(20000, 1/4): standard deviation 0.003.
  EXPECT_NEAR(in_first / 20000.0, 0.25, 0.015);
  // Uniform within the big triangle: the part x > 1.5 holds 1 - 1/4 of its area.
  int right = 0;
  for (const Vec3& p : samples) right += p.x() > 1.5;
  EXPECT_NEAR(right / 20000.0, 0.75 * 0.75, 0.015);
}

TEST(SampleSurface, RejectsMeshesWithoutArea) {
  TriangleMesh flat;
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  flat.faces = {{0, 1, 2}};
  EXPECT_THROW(sample_surface(flat, 10, 0), std::invalid_argument);
  EXPECT_THROW(sample_surface(TriangleMesh{}, 10, 0), std::invalid_argument);
  flat.faces = {{0, 1, 3}};
  EXPECT_THROW(surface_area(flat), std::invalid_argument);
}

TEST(CompareSurfaces, IdenticalMeshesAreAtDistanceZero) {
  const TriangleMesh m = icosphere(3);
  const SurfaceDistance d = compare_surfaces(m, m, with_samples(20000));
  EXPECT_LT(d.hausdorff, 1e-12);
  EXPECT_LT(d.a_to_b.mean, 1e-12);
  EXPECT_LT(d.b_to_a.rms, 1e-12);
  EXPECT_EQ(d.precision, 1.0);
  EXPECT_EQ(d.recall, 1.0);
  EXPECT_EQ(d.fscore, 1.0);
  EXPECT_EQ(d.a_to_b.samples, 20000u);
  EXPECT_EQ(d.b_to_a.samples, 20000u);
}

// B = 1.01 A for a convex A inscribed in the unit sphere whose face planes
// are at least h from the centre: a point p of A is at least 0.01 h from every
// face plane of B (and B's points from A's planes), and at most 0.01 |p| <= 0.01
// from 1.01 p, so every sample distance, both ways, lies in [0.01 h, 0.01].
// For level 4, 1 - h is 9e-4.
TEST(CompareSurfaces, ScaledSphereIsAtTheOffset) {
  const TriangleMesh a = icosphere(4);
  const TriangleMesh b = transformed(a, 1.01);
  const double h = nearest_face_plane(a);
  ASSERT_GT(h, 0.998);
  const SurfaceDistance d = compare_surfaces(a, b, with_samples(20000));
  const double lo = 0.01 * h * (1 - 1e-9), hi = 0.01 * (1 + 1e-9);
  for (const OneSidedDistance& side : {d.a_to_b, d.b_to_a}) {
    EXPECT_GE(side.mean, lo);
    EXPECT_LE(side.mean, hi);
    EXPECT_GE(side.rms, lo);
    EXPECT_LE(side.rms, hi);
    EXPECT_GE(side.max, lo);
    EXPECT_LE(side.max, hi);
  }
  EXPECT_GE(d.hausdorff, lo);
  EXPECT_LE(d.hausdorff, hi);
  EXPECT_NEAR(d.chamfer_l1, 0.01, 1e-5);
  // Relative values use B's bounding-box diagonal.
  Eigen::AlignedBox3d box;
  for (const Vec3& v : b.vertices) box.extend(v);
  EXPECT_DOUBLE_EQ(d.diagonal, box.diagonal().norm());
  EXPECT_DOUBLE_EQ(d.relative(d.hausdorff), d.hausdorff / d.diagonal);
  EXPECT_DOUBLE_EQ(d.threshold, 0.005 * d.diagonal);
}

// For a sphere moved by t, a point with normal n is about |t . n| from the
// original: distances spread uniformly over [0, |t|] (|cos| is uniform on the
// sphere), so the Hausdorff distance is |t|, the mean |t| / 2, the fraction
// within τ < |t| is τ / |t|. The flattening of the icosphere (9e-4, 1.2 % of
// |t|) and the sampling (a sample within ~0.02 rad of the extreme, the means
// of 20000 samples) keep every value within 3 % of |t|.
TEST(CompareSurfaces, TranslatedSphereHausdorffIsTheTranslation) {
  const TriangleMesh a = icosphere(4);
  const Vec3 t(0.06, 0.04, -0.02);
  const TriangleMesh b = transformed(a, 1.0, t);
  const double tau = t.norm() / 2;
  CompareOptions options = with_samples(20000);
  const double diagonal = compare_surfaces(a, b, with_samples(10)).diagonal;
  options.fscore_threshold = tau / diagonal;
  const SurfaceDistance d = compare_surfaces(a, b, options);
  EXPECT_NEAR(d.hausdorff, t.norm(), 0.03 * t.norm());
  EXPECT_NEAR(d.a_to_b.max, t.norm(), 0.03 * t.norm());
  EXPECT_NEAR(d.b_to_a.max, t.norm(), 0.03 * t.norm());
  EXPECT_NEAR(d.a_to_b.mean, t.norm() / 2, 0.03 * t.norm());
  EXPECT_NEAR(d.b_to_a.mean, t.norm() / 2, 0.03 * t.norm());
  // rms of |t| u for u uniform on [0, 1]: |t| / sqrt(3).
  EXPECT_NEAR(d.a_to_b.rms, t.norm() / std::sqrt(3.0), 0.03 * t.norm());
  EXPECT_NEAR(d.threshold, tau, 1e-15);
  EXPECT_NEAR(d.precision, 0.5, 0.03);
  EXPECT_NEAR(d.recall, 0.5, 0.03);
  EXPECT_NEAR(d.fscore, 0.5, 0.03);
}

// A cap of a sphere against the whole sphere: the cap lies on the sphere (A->B
// is 0), most of the sphere is far from the cap (B->A is large).
TEST(CompareSurfaces, PatchOfASurfaceIsOneSided) {
  const TriangleMesh sphere = icosphere(3);
  TriangleMesh cap = sphere;
  cap.faces.clear();
  for (const auto& f : sphere.faces)
    if ((sphere.vertices[f[0]] + sphere.vertices[f[1]] + sphere.vertices[f[2]]).z() > 3 * 0.7)
      cap.faces.push_back(f);
  ASSERT_GT(cap.faces.size(), 50u);
  const SurfaceDistance d = compare_surfaces(cap, sphere, with_samples(20000));
  EXPECT_LT(d.a_to_b.max, 1e-12);
  EXPECT_EQ(d.precision, 1.0);
  // The south pole is about |(0.71, 0, 0.7) - (0, 0, -1)| = 1.84 from the cap's rim.
  EXPECT_GT(d.b_to_a.max, 1.7);
  EXPECT_LT(d.b_to_a.max, 2.0);
  EXPECT_GT(d.b_to_a.mean, 0.5);
  EXPECT_EQ(d.hausdorff, d.b_to_a.max);
  // The cap is about (1 - 0.7) / 2 = 15 % of the sphere's area.
  EXPECT_NEAR(d.recall, 0.15, 0.03);
  EXPECT_LT(d.fscore, 0.3);
}

TEST(CompareSurfaces, FScoreFallsWhenTheThresholdGoesBelowTheOffset) {
  const TriangleMesh a = icosphere(4);
  const TriangleMesh b = transformed(a, 1.01);
  const double diagonal = compare_surfaces(a, b, with_samples(10)).diagonal;
  const double h = nearest_face_plane(a);
  double previous = 2;
  for (const double tau : {0.02, 0.0101, 0.0099, 0.005}) {
    const SurfaceDistance d = compare_surfaces(a, b, with_samples(5000, tau / diagonal));
    EXPECT_LE(d.fscore, previous) << "tau " << tau;
    previous = d.fscore;
    if (tau > 0.01) {
      EXPECT_EQ(d.fscore, 1.0) << "tau " << tau;
    } else if (tau < 0.01 * h) {
      EXPECT_EQ(d.fscore, 0.0) << "tau " << tau;
    }
  }
}

TEST(CompareSurfaces, SameSeedSameResultOtherSeedClose) {
  const TriangleMesh a = icosphere(4);
  const TriangleMesh b = transformed(a, 1.0, Vec3(0.02, 0, 0));
  const CompareOptions options = with_samples(20000);
  const SurfaceDistance d1 = compare_surfaces(a, b, options);
  const SurfaceDistance d2 = compare_surfaces(a, b, options);
  EXPECT_EQ(d1.hausdorff, d2.hausdorff);
  EXPECT_EQ(d1.a_to_b.mean, d2.a_to_b.mean);
  EXPECT_EQ(d1.b_to_a.mean, d2.b_to_a.mean);
  EXPECT_EQ(d1.a_to_b.rms, d2.a_to_b.rms);
  EXPECT_EQ(d1.b_to_a.rms, d2.b_to_a.rms);
  EXPECT_EQ(d1.fscore, d2.fscore);
  EXPECT_EQ(sample_surface(a, 100, 3), sample_surface(a, 100, 3));

  CompareOptions other = options;
  other.seed = 1;
  const SurfaceDistance d3 = compare_surfaces(a, b, other);
  EXPECT_NE(d1.a_to_b.mean, d3.a_to_b.mean);
  EXPECT_NEAR(d1.a_to_b.mean, d3.a_to_b.mean, 3e-4);
}

TEST(CompareSurfaces, RejectsBadArguments) {
  const TriangleMesh m = icosphere(1);
  EXPECT_THROW(compare_surfaces(m, TriangleMesh{}), std::invalid_argument);
  EXPECT_THROW(compare_surfaces(TriangleMesh{}, m), std::invalid_argument);
  EXPECT_THROW(compare_surfaces(m, m, with_samples(0)), std::invalid_argument);
  EXPECT_THROW(compare_surfaces(m, m, with_samples(10, -1)), std::invalid_argument);
  EXPECT_THROW(compare_surfaces(m, m, with_samples(CompareOptions::kMaxSamples + 1)),
               std::invalid_argument);
}

TEST(CompareSurfaces, MeshesOutOfTheMeasurableRangeAreNamed) {
  TriangleMesh m = icosphere(1);
  EXPECT_NO_THROW(require_area(m, "unit"));
  for (Vec3& v : m.vertices) v *= 1e160;
  try {
    require_area(m, "big.ply");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("big.ply: the vertices span 3.46e+160", 0), 0u)
        << e.what();
  }
  for (Vec3& v : m.vertices) v = v * 1e-160 * 1e-160;  // 3.46e-160 across
  EXPECT_THROW(require_area(m, "small.ply"), InputError);
  // A result that is not finite is never reported.
  SurfaceDistance d;
  d.diagonal = 1;
  d.hausdorff = std::nan("");
  EXPECT_THROW(comparison_report("a", "b", CompareOptions{}, d, true), InputError);
  d.hausdorff = 1;
  EXPECT_NO_THROW(comparison_report("a", "b", CompareOptions{}, d, true));
}

// ------------------------------------------------------------ command line

namespace fs = std::filesystem;

class CompareCli : public test::ScratchDirTest {
 protected:
  // Runs `pdd <args>`; returns the exit code, stdout in out_, stderr in err_.
  int pdd(const std::string& args) {
    const test::Outcome outcome = run(PDD_BINARY, args);
    out_ = outcome.out;
    err_ = outcome.err;
    return outcome.code;
  }

  std::string out_, err_;
};

// The number after "key": in a JSON text; NaN when the key is missing or its
// value is not a number.
double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  const std::regex pattern("\"" + key + "\": (-?[0-9][0-9.eE+-]*)[,\n]");
  return std::regex_search(json, m, pattern) ? std::stod(m[1]) : std::nan("");
}

TEST_F(CompareCli, JsonHasTheDistances) {
  write_mesh(path("a.ply"), icosphere(3));
  write_mesh(path("b.off"), transformed(icosphere(3), 1.01));
  ASSERT_EQ(pdd("compare " + path("a.ply") + " " + path("b.off") + " --json --samples 5000"), 0)
      << err_;
  EXPECT_EQ(out_.front(), '{');
  EXPECT_EQ(out_.substr(out_.size() - 2), "}\n");
  // Level 3's faces are up to 3.6e-3 inside the unit sphere: distances in [0.00996, 0.01].
  EXPECT_NEAR(json_number(out_, "hausdorff"), 0.01, 5e-5);
  EXPECT_NEAR(json_number(out_, "chamfer_l1"), 0.01, 5e-5);
  EXPECT_NEAR(json_number(out_, "mean_a_to_b"), 0.01, 5e-5);
  EXPECT_NEAR(json_number(out_, "rms_b_to_a"), 0.01, 5e-5);
  EXPECT_EQ(json_number(out_, "samples"), 5000);
  const double diagonal = json_number(out_, "diagonal_b");
  EXPECT_GT(diagonal, 3.4);
  EXPECT_NEAR(json_number(out_, "hausdorff_relative"), json_number(out_, "hausdorff") / diagonal,
              1e-8);
  // τ = 0.5 % of B's diagonal (about 0.0175) is above the offset 0.01.
  EXPECT_NEAR(json_number(out_, "fscore_threshold"), 0.005 * diagonal, 1e-8);
  EXPECT_EQ(json_number(out_, "fscore"), 1);
  EXPECT_EQ(json_number(out_, "precision"), 1);
  for (const char* key : {"mean_b_to_a", "rms_a_to_b", "max_a_to_b", "max_b_to_a", "recall",
                          "chamfer_l1_relative", "fscore_threshold_relative"})
    EXPECT_FALSE(std::isnan(json_number(out_, key))) << key << " in\n" << out_;

  ASSERT_EQ(pdd("compare " + path("a.ply") + " " + path("b.off") +
                " --json --samples 5000 --fscore-threshold 0.002"),
            0);
  EXPECT_EQ(json_number(out_, "fscore"), 0);  // τ = 0.007 < 0.00996
}

TEST_F(CompareCli, TextNamesTheReference) {
  write_mesh(path("a.obj"), icosphere(2));
  ASSERT_EQ(pdd("compare " + path("a.obj") + " " + path("a.obj") + " --samples 1000"), 0) << err_;
  EXPECT_NE(out_.find("Hausdorff"), std::string::npos) << out_;
  EXPECT_NE(out_.find("(reference)"), std::string::npos) << out_;
  EXPECT_NE(out_.find("F-score"), std::string::npos) << out_;
}

TEST_F(CompareCli, BadInputExitsWithTwo) {
  write_mesh(path("a.ply"), icosphere(1));
  EXPECT_EQ(pdd("compare " + path("a.ply") + " " + path("missing.ply")), 2);
  EXPECT_NE(err_.find("missing.ply"), std::string::npos) << err_;

  TriangleMesh flat;
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  flat.faces = {{0, 1, 2}};
  write_mesh(path("flat.ply"), flat);
  EXPECT_EQ(pdd("compare " + path("flat.ply") + " " + path("a.ply")), 2);
  EXPECT_NE(err_.find("flat.ply: the mesh has no area"), std::string::npos) << err_;

  EXPECT_EQ(pdd("compare " + path("a.ply") + " " + path("a.ply") + " --samples 0"), 2);
  EXPECT_EQ(pdd("compare " + path("a.ply")), 2);
}

}  // namespace
}  // namespace pdd
