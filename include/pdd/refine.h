// Adaptive refinement of the domain around the isosurface (§3.4): trisection
// and bisection of the tets crossed by f = 0, driven by a sizing field.
#pragma once

#include <pdd/domain.h>
#include <pdd/sizing.h>

#include <random>

namespace pdd {

// Isofacet areas against their targets.
struct IsofacetAreaStats {
  int count = 0;
  double mean_area = 0;
  double max_area = 0;
  double mean_ratio = 0;  // mean of r_t = area / s
  double max_ratio = 0;
  int above_4 = 0;        // facets whose larger contour triangle is 4x the target (sizing_met)
  int away = 0;           // facets away from the data (SizingField::target_areas_marking_away)
  int above_4_away = 0;   // of them, counted in above_4
};

struct RefinementStats {
  int crossing_tets = 0;
  int trisected = 0;
  int bisected = 0;
  int left = 0;            // crossing tets not refined
  int inserted_points = 0;
  IsofacetAreaStats before;  // on the domain given (the refined one's: isofacet_area_stats)
};

// The rules of §3.4 for one tet: r_t = area / target; returns 3 to trisect,
// 2 to bisect, 0 to leave it. `draw` is a uniform sample in [0, 1) used in
// rule 5 (bisect with probability (r_t - 1) / 3 when 1 < r_t < 4).
int refinement_rule(const Isofacet& facet, double ratio, double draw);

// One refinement pass: evaluates the sizing field on every crossing tet,
// applies the rules, and inserts the trisection points (two per edge and the
// centroid of each face, Figure 6b) or bisection points (the midpoint of
// each edge whose ends have the same sign, Figure 6c-d). Points shared by
// neighbouring tets are inserted once; points on the domain's boundary are
// not inserted, so the boundary sphere stays as initialized; new vertices
// get f by interpolation.
RefinementStats refine(Domain& domain, const SizingField& sizing, std::mt19937_64& rng);

IsofacetAreaStats isofacet_area_stats(const std::vector<Isofacet>& facets,
                                      const std::vector<double>& targets,
                                      const std::vector<char>& away = {});

// The isofacets of the domain's f against the sizing field.
IsofacetAreaStats isofacet_area_stats(const Domain& domain, const SizingField& sizing);

// The sizing field is met: isofacets are on average no larger than their
// target and almost none of those near the data gives the output a triangle
// of 4x the target (a triangle facet with r_t >= 4, or a quadrangle whose
// larger half, as the contour cuts it, is that large). A few such facets are
// tolerated (`max_fraction_above_4` of the facets near the data): the solve
// after each pass moves the isosurface, so a handful of large facets reappear
// on every iteration and a strict bound would add iterations that change
// nothing but the vertex count. Away from the data (holes, a scan's unseen
// side) the invented surface moves most between solves: its 4x facets are
// not counted.
bool sizing_met(const IsofacetAreaStats& stats, double max_fraction_above_4 = 0.002);

}  // namespace pdd
