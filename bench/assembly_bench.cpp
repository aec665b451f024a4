// The SSD matrix's squared-Hessian term (hessian_energy, Eq. 11 and 15): its
// time and the memory it adds over the domain, on random domains of a given
// size (issue 15: it was the peak of a 1M-point run).
//
//   assembly_bench [--sizes 200000,1000000] [--rounds 3]
//
// Per size: the domain (points uniform in a ball, inserted in random order,
// as the refiner's batches are not spatially sorted), then ROUNDS assemblies,
// each with its wall seconds and the peak resident memory it added (VmHWM
// reset through /proc/self/clear_refs before each), and the result's non-zeros.
#include <pdd/domain.h>
#include <pdd/fem.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

// A field of /proc/self/status in MB.
double status_mb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field, 0) == 0) return std::stod(line.substr(std::strlen(field))) / 1024.0;
  return -1;
}

void reset_peak() { std::ofstream("/proc/self/clear_refs") << "5"; }

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes = {200000, 1000000};
  int rounds = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream list(argv[i + 1]);
      for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::stoul(item));
    } else if (!std::strcmp(argv[i], "--rounds")) {
      rounds = std::stoi(argv[i + 1]);
    } else {
      std::cerr << "usage: assembly_bench [--sizes N,N...] [--rounds R]\n";
      return 2;
    }
  }
  for (std::size_t n : sizes) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    pdd::PointSet seed;
    for (int i = 0; i < 1000; ++i) {
      const pdd::Vec3 p(u(rng), u(rng), u(rng));
      seed.points.push_back(0.8 * p.normalized());
      seed.normals.push_back(p.normalized());
    }
    pdd::Domain domain = pdd::Domain::initial(seed);
    std::vector<pdd::Vec3> points;
    while (points.size() + domain.num_vertices() < n) {
      const pdd::Vec3 p(u(rng), u(rng), u(rng));
      if (p.norm() < 0.9) points.push_back(0.9 * domain.radius() * p + domain.center());
    }
    domain.insert(points);
    const pdd::TetMesh& mesh = domain.mesh();
    std::printf("%zu vertices, %zu tets, %.0f MB resident before\n", mesh.vertices.size(),
                mesh.tets.size(), status_mb("VmRSS:"));
    for (int r = 0; r < rounds; ++r) {
      const double before = status_mb("VmRSS:");
      reset_peak();
      const auto start = std::chrono::steady_clock::now();
      const pdd::SparseMatrix energy = pdd::hessian_energy(mesh);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("  hessian_energy: %.2f s, peak +%.0f MB (%.0f bytes per vertex), "
                  "%ld non-zeros\n",
                  seconds, status_mb("VmHWM:") - before,
                  (status_mb("VmHWM:") - before) * 1048576.0 / mesh.vertices.size(),
                  static_cast<long>(energy.nonZeros()));
    }
  }
  return 0;
}
