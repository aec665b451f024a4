// The trim and the clean-up alone, on a raw closed isosurface (issue 16): what
// `pdd reconstruct --trim D` does after the loop, without re-running the loop.
// RAW is the output of `pdd reconstruct INPUT -o RAW --no-cleanup` (its small,
// open and unsupported components already removed; the loop does not depend on
// --trim); POINTS is the run's input, all of whose points the trim is given,
// as the run gives them (outliers included).
//
//   trim_bench RAW POINTS OUT [--trim D] [--trim-holes H] [--trim-islands I]
//
// Writes OUT (trimmed with D > 0, closed with D = 0, then cleaned up) and one
// line: the trim's report and its seconds, and the clean-up's. Trimmed and
// closed outputs of one RAW compare the trim alone (bench/results/real_scans_trim_parity.md).
#include <pdd/contour.h>
#include <pdd/io.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr
        << "usage: trim_bench RAW POINTS OUT [--trim D] [--trim-holes H] [--trim-islands I]\n";
    return 2;
  }
  pdd::TrimOptions trim;
  trim.distance = 2;
  for (int i = 4; i + 1 < argc; i += 2) {
    const double value = std::stod(argv[i + 1]);
    if (!std::strcmp(argv[i], "--trim")) {
      trim.distance = value;
    } else if (!std::strcmp(argv[i], "--trim-holes")) {
      trim.holes = value;
    } else if (!std::strcmp(argv[i], "--trim-islands")) {
      trim.islands = value;
    } else {
      std::cerr << "trim_bench: unknown option " << argv[i] << "\n";
      return 2;
    }
  }
  pdd::TriangleMesh mesh = pdd::read_mesh(argv[1]);
  mesh.attributes.clear();  // the trim and the clean-up do not carry the raw mesh's colours
  const pdd::PointSet points = pdd::read_points(argv[2]);

  using Clock = std::chrono::steady_clock;
  auto t = Clock::now();
  const pdd::TrimReport r = pdd::trim_to_samples(mesh, points.points, trim);
  const double trim_s = std::chrono::duration<double>(Clock::now() - t).count();
  t = Clock::now();
  pdd::cleanup_isosurface(mesh);
  const double cleanup_s = std::chrono::duration<double>(Clock::now() - t).count();
  pdd::write_mesh(argv[3], mesh);
  std::printf(
      "faces %zu area_removed %.4f holes_kept %d islands %d (%d faces) loops %d "
      "trim %.2f s cleanup %.2f s\n",
      mesh.faces.size(), r.area_removed, r.holes_kept, r.islands.components, r.islands.faces,
      r.boundary_loops, trim_s, cleanup_s);
  return 0;
}
