// --save-iterations: every iteration's isosurface and domain as files (Figure 7).
#include <pdd/io.h>
#include <pdd/report.h>

#include <cstdio>
#include <filesystem>

namespace pdd {

IterationCallback iteration_files(const std::string& folder, bool ascii, StagedOutputs* staged) {
  check_output_path(folder, OutputKind::kFolder);
  if (staged) {
    staged->create_folder(folder);
  } else {
    std::filesystem::create_directories(folder);
  }
  return [folder, ascii, staged](const IterationStats& stats, const Domain& domain,
                                 const TriangleMesh& isosurface) {
    char name[64];
    std::snprintf(name, sizeof name, "/iteration_%02d", stats.iteration);
    write_mesh(folder + name + "_isosurface.ply", isosurface, {ascii, staged});
    write_domain_vtu(folder + name + "_domain.vtu", domain.mesh(), domain.f(), {}, {}, staged);
  };
}

}  // namespace pdd
