// pdd: surface reconstruction by progressive discrete domains.
// A thin client of the library: parses options, calls pdd::, reports errors.
#include "commands.h"
#include "huge_pages.h"
#include "signals.h"

#include <pdd/errors.h>

#include <malloc.h>

#include <iostream>

int main(int argc, char** argv) {
  pdd::cli::start_signal_watcher(argv, pdd::cli::ask_for_huge_pages());  // may start over once
  // Each iteration assembles and factors matrices of hundreds of megabytes and
  // frees them again. With glibc's defaults every such block is a fresh mmap
  // whose pages the kernel zeroes on first touch (a third of the run was
  // system time on a 20k-point scan); keeping freed memory in the heap for
  // reuse halves that (docs/benchmarks.md, "Where the time goes").
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  // One heap for all threads: what a worker frees (half of each concurrently
  // built triangulation) is then reused by the next step on any thread, not
  // held in the worker's own arena (building.ply's resident peak 1.00 -> 0.85
  // GB at the same speed).
  mallopt(M_ARENA_MAX, 1);
  CLI::App app{"pdd: closed triangle meshes from point clouds by progressive discrete domains\n"
               "(Zhao, Alliez, Boubekeur, Buse, Thiery, SGP 2021)"};
  app.set_version_flag("--version", std::string("pdd ") + PDD_VERSION);
  app.require_subcommand(1);
  pdd::cli::add_reconstruct_command(app);
  pdd::cli::add_quality_command(app);
  pdd::cli::add_compare_command(app);
  pdd::cli::add_normals_command(app);

  // Exit codes: 0 success, 1 runtime failure, 2 bad usage or bad input.
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "pdd: error: " << e.what() << " (see pdd --help)\n";
    return 2;
  } catch (const pdd::cli::Interrupted&) {
    std::cerr << "pdd: interrupted\n";
    return pdd::cli::cancel_exit_code();
  } catch (const pdd::InputError& e) {
    std::cerr << "pdd: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pdd: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
