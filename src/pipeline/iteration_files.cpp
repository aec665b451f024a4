// --save-iterations: every iteration's isosurface and domain as files (Figure 7).
#include <pdd/io.h>
#include <pdd/report.h>

#include <cstdio>
#include <filesystem>

namespace pdd {

IterationCallback iteration_files(const std::string& folder, bool ascii) {
  check_output_path(folder, OutputKind::kFolder);
  std::filesystem::create_directories(folder);
  return [folder, ascii](const IterationStats& stats, const Domain& domain,
                         const TriangleMesh& isosurface) {
    char name[64];
    std::snprintf(name, sizeof name, "/iteration_%02d", stats.iteration);
    write_mesh(folder + name + "_isosurface.ply", isosurface, {ascii});
    write_domain_vtu(folder + name + "_domain.vtu", domain.mesh(), domain.f());
  };
}

}  // namespace pdd
