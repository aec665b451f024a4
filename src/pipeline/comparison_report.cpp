// The report of `pdd compare` and pdd.compare(): two-sided distances between
// two meshes, as text or JSON.
#include <pdd/errors.h>
#include <pdd/report.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "common/json.h"

namespace pdd {
namespace {

struct Names {
  const std::string& a;
  const std::string& b;
  const CompareOptions& options;
};

std::string json(const Names& args, const SurfaceDistance& d) {
  std::ostringstream o;
  auto value = [&o](const std::string& key, const std::string& v, bool last = false) {
    o << "  " << json_string(key) << ": " << v << (last ? "\n" : ",\n");
  };
  // A distance, then the same relative to B's diagonal.
  auto distance = [&](const std::string& key, double v) {
    value(key, significant(v, 9));
    value(key + "_relative", significant(d.relative(v), 9));
  };
  o << "{\n";
  value("a", json_string(args.a));
  value("b", json_string(args.b));
  value("samples", std::to_string(args.options.samples));
  value("seed", std::to_string(args.options.seed));
  value("relative_to", json_string("bounding-box diagonal of b"));
  value("diagonal_b", significant(d.diagonal, 9));
  distance("hausdorff", d.hausdorff);
  distance("chamfer_l1", d.chamfer_l1);
  distance("mean_a_to_b", d.a_to_b.mean);
  distance("mean_b_to_a", d.b_to_a.mean);
  distance("rms_a_to_b", d.a_to_b.rms);
  distance("rms_b_to_a", d.b_to_a.rms);
  distance("max_a_to_b", d.a_to_b.max);
  distance("max_b_to_a", d.b_to_a.max);
  distance("fscore_threshold", d.threshold);
  value("precision", significant(d.precision, 9));
  value("recall", significant(d.recall, 9));
  value("fscore", significant(d.fscore, 9), true);
  o << "}\n";
  return o.str();
}

std::string text(const Names& args, const SurfaceDistance& d) {
  std::ostringstream o;
  auto row = [&o, &d](const char* name, double v) {
    char line[128];
    std::snprintf(line, sizeof line, "  %-12s %14s %12s %%\n", name, significant(v, 6).c_str(),
                  number(100 * d.relative(v), 4).c_str());
    o << line;
  };
  o << "A: " << args.a << "\n"
    << "B: " << args.b << " (reference)\n"
    << args.options.samples << " area-uniform samples on each surface (seed " << args.options.seed
    << "); relative to B's bounding-box diagonal " << significant(d.diagonal, 6) << "\n"
    << "                     distance     relative\n";
  row("Hausdorff", d.hausdorff);
  row("Chamfer-L1", d.chamfer_l1);
  row("mean A->B", d.a_to_b.mean);
  row("mean B->A", d.b_to_a.mean);
  row("RMS A->B", d.a_to_b.rms);
  row("RMS B->A", d.b_to_a.rms);
  row("max A->B", d.a_to_b.max);
  row("max B->A", d.b_to_a.max);
  o << "F-score at " << number(100 * args.options.fscore_threshold, 3) << " % of the diagonal ("
    << significant(d.threshold, 6) << "): " << number(d.fscore, 4) << "  (precision "
    << number(d.precision, 4) << ", recall " << number(d.recall, 4) << ")\n";
  return o.str();
}

}  // namespace

std::string comparison_report(const std::string& a, const std::string& b,
                              const CompareOptions& options, const SurfaceDistance& distance,
                              bool as_json) {
  // A NaN or an overflow is never reported as a result.
  const SurfaceDistance& d = distance;
  for (const double v : {d.diagonal, d.threshold, d.hausdorff, d.chamfer_l1, d.a_to_b.mean,
                         d.b_to_a.mean, d.a_to_b.rms, d.b_to_a.rms, d.a_to_b.max, d.b_to_a.max,
                         d.precision, d.recall, d.fscore})
    if (!std::isfinite(v))
      throw InputError(a + ", " + b + ": a distance between the meshes comes out " +
                       (std::isnan(v) ? "NaN" : "infinite") +
                       "; their coordinates are out of the range it can be computed in");
  const Names names{a, b, options};
  return as_json ? json(names, distance) : text(names, distance);
}

}  // namespace pdd
