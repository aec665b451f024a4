#include <pdd/report.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

namespace pdd {
namespace {

// Shortest text that reads back to the same double; JSON has no inf/nan.
std::string number(double x) {
  if (!std::isfinite(x)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace

std::string statistics_json(const Result& result, const ReconstructOptions& options) {
  std::ostringstream out;
  out << "{\n  \"strategy\": \"" << to_string(options.strategy) << "\",\n"
      << "  \"solver\": \"" << to_string(options.solver.kind) << "\",\n"
      << "  \"seed\": " << options.seed << ",\n"
      << "  \"noise\": " << number(result.noise) << ",\n"
      << "  \"seconds\": " << number(result.seconds) << ",\n"
      << "  \"vertices\": " << result.domain.num_vertices() << ",\n"
      << "  \"triangles\": " << result.mesh.faces.size() << ",\n"
      << "  \"isovertices\": " << result.mesh.vertices.size() << ",\n"
      << "  \"normals\": {\"mode\": \"" << to_string(options.normals)
      << "\", \"estimated\": " << (result.normals.estimated ? "true" : "false")
      << ", \"oriented\": " << (result.normals.oriented ? "true" : "false")
      << ", \"orientation\": \"" << to_string(result.normals.orientation)
      << "\", \"neighbors\": "
      << (result.normals.neighbors > 0 ? result.normals.neighbors : options.normal_neighbors)
      << ", \"smoothed\": " << (result.normals.smoothed ? "true" : "false")
      << ", \"flipped\": " << result.normals.flipped
      << ", \"unreached\": " << result.normals.unreached
      << ", \"segments\": " << result.normals.segments
      << ", \"unclear\": " << result.normals.unclear
      << ", \"sharpened\": " << result.normals.sharpened
      << ", \"filled\": " << result.normals.filled
      << ", \"seconds\": " << number(result.normals.seconds) << "},\n"
      << "  \"outliers\": {\"ratio\": " << number(result.outliers.ratio)
      << ", \"neighbors\": " << result.outliers.neighbors
      << ", \"removed\": " << result.outliers.removed
      << ", \"median_spacing\": " << number(result.outliers.median_spacing) << "},\n"
      << "  \"trim\": {\"trimmed\": " << (result.trim.trimmed ? "true" : "false")
      << ", \"distance\": " << number(options.trim.distance)
      << ", \"holes\": " << number(options.trim.holes)
      << ", \"islands\": " << number(options.trim.islands)
      << ", \"spacing\": " << number(result.trim.spacing)
      << ", \"area_removed\": " << number(result.trim.area_removed)
      << ", \"holes_kept\": " << result.trim.holes_kept
      << ", \"islands_removed\": " << result.trim.islands.components
      << ", \"island_faces_removed\": " << result.trim.islands.faces
      << ", \"boundary_loops\": " << result.trim.boundary_loops << "},\n"
      << "  \"attributes\": [";
  for (std::size_t a = 0; a < result.mesh.attributes.size(); ++a)
    out << (a ? ", " : "") << "\"" << result.mesh.attributes[a].name << "\"";
  out << "],\n"
      << "  \"memory_budget\": {\"bytes\": " << result.budget.bytes
      << ", \"vertices\": " << result.budget.vertices
      << ", \"predicted_vertices\": " << result.budget.predicted_vertices
      << ", \"coarsening\": " << number(result.budget.coarsening)
      << ", \"refinement_stopped\": " << (result.budget.refinement_stopped ? "true" : "false")
      << ", \"input_vertices\": " << result.budget.input_vertices
      << ", \"limited_by_input\": " << (result.budget.limited_by_input ? "true" : "false")
      << "},\n"
      << "  \"iterations\": [";
  for (std::size_t i = 0; i < result.iterations.size(); ++i) {
    const IterationStats& s = result.iterations[i];
    out << (i ? "," : "") << "\n    {"
        << "\"iteration\": " << s.iteration << ", \"final\": "
        << (i + 1 == result.iterations.size() ? "true" : "false")
        << ", \"vertices\": " << s.vertices
        << ", \"vertices_near_isosurface\": " << s.vertices_near_isosurface
        << ", \"parsimony\": " << number(s.parsimony) << ", \"isovertices\": " << s.isovertices
        << ", \"triangles\": " << s.triangles << ", \"solver_method\": \"" << s.solver.method
        << "\", \"solver_iterations\": " << s.solver.iterations
        << ", \"solver_levels\": " << s.solver.levels
        << ", \"solver_residual\": " << number(s.solver.residual)
        << ", \"value_weight\": " << number(s.solver.value_weight)
        << ", \"optimizer_cg_iterations\": " << s.optimizer_cg_iterations
        << ", \"rejected_moves\": " << s.rejected_moves << ", \"trisected\": " << s.trisected
        << ", \"bisected\": " << s.bisected << ", \"inserted_points\": " << s.inserted_points
        << ", \"crossing_tets\": " << s.crossing_tets
        << ", \"mean_area_ratio\": " << number(s.mean_area_ratio) << ", \"above_4\": " << s.above_4
        << ", \"away_from_data\": " << s.away_from_data
        << ", \"above_4_away_from_data\": " << s.above_4_away_from_data
        << ", \"mean_min_angle\": " << number(s.mean_min_angle)
        << ", \"fraction_below_30\": " << number(s.fraction_below_30)
        << ", \"seconds\": {\"solve\": " << number(s.seconds_solve)
        << ", \"solve_assembly\": " << number(s.solver.assembly_seconds)
        << ", \"solve_factorize\": " << number(s.solver.factorize_seconds)
        << ", \"solve_linear\": " << number(s.solver.solve_seconds)
        << ", \"optimize\": " << number(s.seconds_optimize)
        << ", \"refine\": " << number(s.seconds_refine)
        << ", \"contour\": " << number(s.seconds_contour)
        << ", \"cleanup\": " << number(s.seconds_cleanup) << "}"
        << ", \"removed_components\": " << s.small_components.components
        << ", \"removed_component_faces\": " << s.small_components.faces
        << ", \"removed_open_components\": " << s.open_components.components
        << ", \"removed_open_component_faces\": " << s.open_components.faces
        << ", \"removed_unsupported_components\": " << s.unsupported_components.components
        << ", \"removed_unsupported_component_faces\": " << s.unsupported_components.faces
        << ", \"cut_handles\": " << s.handles.handles
        << ", \"cut_handle_faces\": " << s.handles.faces
        << ", \"cleanup_flips\": " << s.cleanup.flips
        << ", \"cleanup_collapses\": " << s.cleanup.collapses
        << ", \"cleanup_moves\": " << s.cleanup.moves
        << ", \"boundary_edges\": " << s.boundary_edges << "}";
  }
  out << "\n  ]\n}\n";
  return out.str();
}

std::string statistics_table(const Result& result) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%5s %9s %9s %6s %9s %9s %7s %6s %7s %7s %7s %7s\n", "iter",
                "vertices", "near-iso", "pars.", "triangles", "residual", "minang", "<30%",
                "solve s", "optim s", "refine s", "contour");
  out << line;
  for (const IterationStats& s : result.iterations) {
    std::snprintf(line, sizeof line, "%5d %9zu %9zu %6.3f %9zu %9.2e %7.2f %6.2f %7.2f %7.2f %7.2f %7.2f\n",
                  s.iteration, s.vertices, s.vertices_near_isosurface, s.parsimony, s.triangles,
                  s.solver.residual, s.mean_min_angle, 100 * s.fraction_below_30, s.seconds_solve,
                  s.seconds_optimize, s.seconds_refine, s.seconds_contour);
    out << line;
  }
  if (!result.iterations.empty()) {
    const IterationStats& last = result.iterations.back();
    for (const auto& [r, kind] : {std::pair(last.small_components, "small"),
                                  std::pair(last.open_components, "open"),
                                  std::pair(last.unsupported_components, "unsupported")})
      if (r.components > 0) {
        std::snprintf(line, sizeof line, "removed %d %s component%s (%d triangles)\n",
                      r.components, kind, r.components == 1 ? "" : "s", r.faces);
        out << line;
      }
    if (last.handles.handles > 0) {
      std::snprintf(line, sizeof line, "cut %d unsupported handle%s (%d triangles, capped)\n",
                    last.handles.handles, last.handles.handles == 1 ? "" : "s", last.handles.faces);
      out << line;
    }
  }
  if (!result.iterations.empty() && result.iterations.back().solver.value_weight > 0) {
    std::snprintf(line, sizeof line,
                  "value weight alpha %.4g in the final solve (noise estimate %.3g)\n",
                  result.iterations.back().solver.value_weight, result.noise);
    out << line;
  }
  std::snprintf(line, sizeof line, "total %.2f s\n", result.seconds);
  out << line;
  return out.str();
}

std::string normals_note(const Result& result) {
  const NormalsReport& n = result.normals;
  if (!n.oriented && n.filled > 0)
    return std::to_string(n.filled) + " zero normal" + (n.filled == 1 ? "" : "s") +
           " replaced by estimated ones (jet fitting), turned as their neighbours'";
  if (!n.oriented) return "";
  const std::string scale =
      n.smoothed ? " over " + std::to_string(n.neighbors) + " neighbours (noisy points)" : "";
  std::string line = std::string("normals ") +
                     (n.estimated ? "estimated by jet fitting" + scale +
                                        (n.sharpened > 0 ? ", " + std::to_string(n.sharpened) +
                                                               " from a flatter neighbourhood"
                                                         : std::string()) +
                                        " and "
                                  : "") +
                     "oriented " +
                     (n.orientation == Orientation::kMst ? "along a minimum spanning tree"
                      : std::to_string(n.segments) + (n.segments == 1 ? " segment" : " segments") +
                            (n.orientation == Orientation::kSpectral
                                 ? " by a coarse spectral run's gradient"
                                 : " towards their open side")) +
                     " (--normals, --orientation): " + std::to_string(n.flipped) + " flipped";
  if (n.unreached > 0) line += ", " + std::to_string(n.unreached) + " not reached by the tree";
  if (n.unclear > 0)
    line += ", " + std::to_string(n.unclear) + " seen from both sides turned by a coarse spectral run";
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, " in %.1f s", n.seconds);
  return line + seconds;
}

std::string outliers_note(const Result& result) {
  const OutlierReport& o = result.outliers;
  if (o.removed == 0) return "";
  char line[240];
  std::snprintf(line, sizeof line,
                "dropped %zu outlier%s: points whose mean distance to their %d nearest is over "
                "%.3g times that of those neighbours (--outliers; 0 keeps all)",
                o.removed, o.removed == 1 ? "" : "s", o.neighbors, o.ratio);
  return line;
}

std::string trim_note(const Result& result) {
  const TrimReport& t = result.trim;
  if (!t.trimmed) return "";
  char line[320];
  std::snprintf(line, sizeof line,
                "trimmed to the samples (--trim): %.1f%% of the area cut away, %d boundary loop%s, "
                "%d small hole%s kept closed, %d island%s of %d triangles dropped",
                100 * t.area_removed, t.boundary_loops, t.boundary_loops == 1 ? "" : "s",
                t.holes_kept, t.holes_kept == 1 ? "" : "s", t.islands.components,
                t.islands.components == 1 ? "" : "s", t.islands.faces);
  return line;
}

std::string open_surface_note(const Result& result) {
  if (result.trim.trimmed || result.iterations.empty()) return "";
  const std::size_t edges = result.iterations.back().boundary_edges;
  if (edges == 0) return "";
  return "the output is open (" + std::to_string(edges) + " boundary edge" +
         (edges == 1 ? "" : "s") +
         "): its surface reaches the domain's boundary, as the points enclose no volume there "
         "(an open scan's unseen side); --trim 2 keeps only the part the points support";
}

std::vector<std::string> run_notes(const Result& result) {
  std::vector<std::string> notes;
  for (std::string note : {outliers_note(result), normals_note(result), memory_budget_note(result),
                           trim_note(result), open_surface_note(result)})
    if (!note.empty()) notes.push_back(std::move(note));
  return notes;
}

std::string memory_budget_note(const Result& result) {
  const MemoryBudget& b = result.budget;
  char line[320];
  const double mb = static_cast<double>(b.bytes) / (1 << 20);
  if (b.limited_by_input && (b.coarsening > 1 || b.refinement_stopped)) {
    std::snprintf(line, sizeof line,
                  "the default sizing would give a domain of %zu vertices, out of proportion to "
                  "the input: kept to about %zu (sizing coarsened %.3gx in area); --target-edge "
                  "asks for a finer mesh",
                  b.predicted_vertices, b.vertices, b.coarsening);
    return line;
  }
  if (b.coarsening > 1) {
    std::snprintf(line, sizeof line,
                  "memory budget %.0f MB (about %zu domain vertices; --max-memory): the sizing "
                  "was coarsened %.3gx in area (%.3gx in edge length) from a predicted %zu "
                  "vertices",
                  mb, b.vertices, b.coarsening, std::sqrt(b.coarsening), b.predicted_vertices);
    return line;
  }
  if (b.refinement_stopped) {
    std::snprintf(line, sizeof line,
                  "memory budget %.0f MB (about %zu domain vertices; --max-memory): refinement "
                  "stopped at %zu vertices before the sizing was met",
                  mb, b.vertices, result.domain.num_vertices());
    return line;
  }
  return "";
}

}  // namespace pdd
