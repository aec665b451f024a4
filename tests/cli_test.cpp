// The `pdd` command line, run as a separate process: exit codes (0 ok, 1
// runtime failure, 2 bad usage or input), one-line error messages, and no
// output file left behind by a failed run.
#include <gtest/gtest.h>
#include <pdd/io.h>
#include <pdd/quality.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#include <gnu/libc-version.h>
#include <sys/stat.h>

#include "support/scratch_dir.h"
#include "support/shapes.h"

namespace pdd {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

std::size_t lines_of(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

class CliTest : public test::ScratchDirTest {
 protected:
  Outcome pdd(const std::string& args) const { return run(PDD_BINARY, args); }
  // The same, killed after a generous 30 s: for inputs that once made it hang.
  Outcome pdd_without_hanging(const std::string& args) const {
    return run("timeout", "30 '" + std::string(PDD_BINARY) + "' " + args);
  }
  std::string quoted_path(const std::string& name) const { return "'" + path(name) + "'"; }
  // Runs each command (killed after 30 s), expecting exit code 2 and one
  // error line that holds the case's message.
  using Cases = std::vector<std::pair<std::string, std::string>>;
  void expect_refused(const Cases& cases) const {
    for (const auto& [command, message] : cases) {
      const Outcome run = pdd_without_hanging(command);
      EXPECT_EQ(run.code, 2) << command << ": " << run.err;
      EXPECT_EQ(lines_of(run.err), 1u) << command << ": " << run.err;
      EXPECT_NE(run.err.find(message), std::string::npos) << command << ": " << run.err;
    }
  }
};

TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

TEST_F(CliTest, HelpAndVersionSucceed) {
  const Outcome help = pdd("--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("reconstruct"), std::string::npos) << help.out;

  const Outcome version = pdd("--version");
  EXPECT_EQ(version.code, 0);
  EXPECT_NE(version.out.find(std::string("pdd ") + PDD_VERSION), std::string::npos) << version.out;

  // The options are named in the paper's terms, with their defaults.
  const Outcome reconstruct = pdd("reconstruct --help");
  EXPECT_EQ(reconstruct.code, 0);
  for (const char* fragment :
       {"--solver", "{ssd,poisson,spectral}=ssd", "--enlarge-ratio", "=1.4", "--sphere-points",
        "=100", "--radius-edge", "=1.3", "--lambda-asap", "--lambda-mid-edge", "--damping",
        "--seed", "--ascii", "--domain", "-o,--output"}) {
    EXPECT_NE(reconstruct.out.find(fragment), std::string::npos) << fragment;
  }
}

TEST_F(CliTest, BadUsageExitsWithTwo) {
  EXPECT_EQ(pdd("").code, 2);
  EXPECT_EQ(pdd("frobnicate").code, 2);
  EXPECT_EQ(pdd("reconstruct").code, 2);
  EXPECT_EQ(pdd("reconstruct in.ply").code, 2);  // no -o
  const Outcome solver = pdd("reconstruct in.ply -o out.ply --solver octree");
  EXPECT_EQ(solver.code, 2);
  EXPECT_NE(solver.err.find("octree"), std::string::npos) << solver.err;
  EXPECT_EQ(pdd("reconstruct in.ply -o out.ply --enlarge-ratio 0.9").code, 2);
  EXPECT_EQ(pdd("reconstruct in.ply -o out.ply --sphere-points many").code, 2);
}

TEST_F(CliTest, MissingInputIsOneLineNamingTheFile) {
  const Outcome run = pdd("reconstruct '" + path("absent.ply") + "' -o '" + path("out.ply") + "'");
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(lines_of(run.err), 1u) << run.err;
  EXPECT_EQ(run.err, "pdd: error: " + path("absent.ply") + ": no such file\n");
  EXPECT_TRUE(entries().empty());
}

TEST_F(CliTest, MalformedInputExitsWithTwo) {
  std::ofstream(path("bad.xyz")) << "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 zero 0 0 1\n0 0 1 0 0 1\n";
  const Outcome run = pdd("reconstruct '" + path("bad.xyz") + "' -o '" + path("out.ply") + "'");
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(lines_of(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find(path("bad.xyz") + ": line 3: 'zero' is not a number"), std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

TEST_F(CliTest, DegenerateInputOrMissingNormalsExitWithTwo) {
  std::ofstream(path("flat.xyz")) << "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n1 1 0 0 0 1\n";
  const Outcome flat = pdd("reconstruct '" + path("flat.xyz") + "' -o '" + path("out.ply") + "'");
  EXPECT_EQ(flat.code, 2);
  EXPECT_NE(flat.err.find("lie in one plane"), std::string::npos) << flat.err;

  // Too few points to estimate normals from.
  PointSet bare = test::sample_sphere(12);
  bare.normals.clear();
  write_points(path("bare.xyz"), bare);
  const Outcome run =
      pdd("reconstruct '" + path("bare.xyz") + "' -o '" + path("out.ply") + "' --solver poisson");
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(lines_of(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find(path("bare.xyz") + ": 12 points are too few to estimate normals from"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

TEST_F(CliTest, PointsWithoutNormalsGetThemAndSaySo) {
  PointSet bare = test::sample_sphere(1500);
  bare.normals.clear();
  write_points(path("bare.xyz"), bare);
  const Outcome run = pdd("reconstruct '" + path("bare.xyz") + "' -o '" + path("out.ply") +
                          "' --target-edge 0.15 --quiet");
  EXPECT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.err.find("pdd: normals estimated by jet fitting and oriented"), std::string::npos)
      << run.err;
  EXPECT_TRUE(surface_topology(read_mesh(path("out.ply"))).closed);

  // `pdd normals` writes what the run used: unit normals, all outward on a sphere.
  const Outcome normals = pdd("normals '" + path("bare.xyz") + "' -o '" + path("n.ply") + "'");
  EXPECT_EQ(normals.code, 0) << normals.err;
  const PointSet with = read_points(path("n.ply"));
  ASSERT_EQ(with.normals.size(), bare.size());
  for (std::size_t i = 0; i < with.size(); ++i) EXPECT_GT(with.normals[i].dot(with.points[i]), 0.99);
}

TEST_F(CliTest, SignalsCancelTheRunAndLeaveNoOutput) {
  write_points(path("in.xyz"), test::sample_sphere(20000));
  // SIGINT during the multigrid run, SIGTERM during CHOLMOD's (METIS's) factorizations;
  // the iterations already saved go too, with the folder made for them;
  // `timeout` sends it after 1.5 s and returns pdd's own exit code, and a second
  // `timeout` kills a run that would hang instead.
  for (const auto& [signal, linear, code] : {std::tuple("INT", "multigrid", 130),
                                             std::tuple("TERM", "cholmod", 143)}) {
    const Outcome run = this->run(
        "timeout", std::string("-s KILL 60 timeout --preserve-status -s ") + signal + " 1.5 '" +
                       PDD_BINARY + "' reconstruct " + quoted_path("in.xyz") + " -o " +
                       quoted_path("out.ply") + " --stats " + quoted_path("out.json") +
                       " --save-iterations " + quoted_path("iterations") +
                       " --target-edge 0.012 --linear " + linear + " --quiet");
    EXPECT_EQ(run.code, code) << signal << ": " << run.err;
    EXPECT_NE(run.err.find("pdd: interrupted"), std::string::npos) << run.err;
    EXPECT_EQ(entries(), std::vector<std::string>{"in.xyz"}) << signal;
  }
}

// Where the kernel gives transparent huge pages to memory that asks and glibc
// can ask (2.35 on), pdd starts over with its heap on them (apps/huge_pages.h),
// unless the caller chose otherwise; the caller's other tunables stay.
TEST_F(CliTest, TheHeapIsOnHugePagesUnlessTheCallerChose) {
  std::ifstream policy("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(policy, line);
  if (line.find("[madvise]") == std::string::npos)
    GTEST_SKIP() << "the kernel's transparent huge pages: '" << line << "'";
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2 ||
      major * 1000 + minor < 2035)
    GTEST_SKIP() << "glibc " << gnu_get_libc_version();
  write_points(path("in.xyz"), test::sample_sphere(20000));
  // The running process's huge pages (kB) a second after the start of a run
  // that takes longer, which is then ended.
  const auto huge_kb_with = [&](const std::string& given) {
    std::ofstream script(path("pages.sh"));
    script << (given.empty() ? "unset GLIBC_TUNABLES\n"
                             : "export GLIBC_TUNABLES='" + given + "'\n")
           << "'" << PDD_BINARY << "' reconstruct " << quoted_path("in.xyz") << " -o "
           << quoted_path("out.ply") << " --target-edge 0.004 --quiet &\n"
           << "sleep 1\nawk '/^AnonHugePages:/ { print $2 }' /proc/$!/smaps_rollup\n"
           << "kill $!\nwait\n";
    script.close();
    const Outcome run = this->run("sh", quoted_path("pages.sh"));
    return run.out.empty() ? -1 : std::stol(run.out);
  };
  EXPECT_GT(huge_kb_with(""), 0);
  EXPECT_GT(huge_kb_with("glibc.malloc.perturb=0"), 0);
  EXPECT_EQ(huge_kb_with("glibc.malloc.hugetlb=0"), 0);
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

TEST_F(CliTest, BadOutputIsRefusedBeforeReading) {
  // The input does not exist: the output's problem is reported first.
  const Outcome stl = pdd("reconstruct '" + path("absent.ply") + "' -o '" + path("out.stl") + "'");
  EXPECT_EQ(stl.code, 2);
  EXPECT_NE(stl.err.find(path("out.stl") + ": unknown extension '.stl'"), std::string::npos)
      << stl.err;
  const Outcome folder =
      pdd("reconstruct '" + path("absent.ply") + "' -o '" + path("no/out.ply") + "'");
  EXPECT_EQ(folder.code, 2);
  EXPECT_NE(folder.err.find("does not exist"), std::string::npos) << folder.err;
  const Outcome domain = pdd("reconstruct '" + path("absent.ply") + "' -o '" + path("out.ply") +
                             "' --domain-out '" + path("d.vtk") + "'");
  EXPECT_EQ(domain.code, 2);
  EXPECT_NE(domain.err.find(path("d.vtk") + ": unknown extension"), std::string::npos)
      << domain.err;
}

TEST_F(CliTest, ReconstructWritesTheMeshStatisticsDomainAndIterations) {
  PointSet points = test::sample_sphere(600);
  points.points.push_back(points.points[5]);
  points.normals.push_back(points.normals[5]);
  points.points.push_back(points.points[9]);
  points.normals.push_back(points.normals[9]);
  write_points(path("in.ply"), points);
  const Outcome run = pdd("reconstruct '" + path("in.ply") + "' -o '" + path("out.ply") +
                          "' --target-edge 0.2 --stats '" + path("stats.json") +
                          "' --domain-out '" + path("d.vtu") + "' --save-iterations '" +
                          path("steps") + "'");
  EXPECT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.err.find("pdd: warning: " + path("in.ply") + ": merged 2 duplicate points"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.out.find("pdd: wrote " + path("out.ply")), std::string::npos) << run.out;
  const TriangleMesh mesh = read_mesh(path("out.ply"));
  EXPECT_GT(mesh.faces.size(), 100u);
  for (const Vec3& v : mesh.vertices) EXPECT_NEAR(v.norm(), 1.0, 0.1);  // half a target edge
  const std::string stats = slurp(path("stats.json"));
  EXPECT_NE(stats.find("\"triangles\": " + std::to_string(mesh.faces.size())), std::string::npos)
      << stats;
  // The samples' value weight under a name that holds for every solver.
  EXPECT_NE(stats.find("\"value_weight\": 60000"), std::string::npos) << stats;
  EXPECT_NE(slurp(path("d.vtu")).find("<UnstructuredGrid>"), std::string::npos);
  EXPECT_TRUE(fs::exists(path("steps/iteration_01_isosurface.ply")));
  EXPECT_TRUE(fs::exists(path("steps/iteration_01_domain.vtu")));
  // Off a terminal, one progress line per stage: the calls from inside a stage print nothing.
  std::istringstream lines(run.err);
  std::vector<std::string> stages;
  for (std::string line; std::getline(lines, line);)
    if (line.find(" iteration ") != std::string::npos) stages.push_back(line.substr(0, 28));
  EXPECT_GT(stages.size(), 5u) << run.err;
  EXPECT_EQ(std::adjacent_find(stages.begin(), stages.end()), stages.end()) << run.err;
}

TEST_F(CliTest, NoCleanupKeepsTheMarchingTetrahedraSurface) {
  write_points(path("in.ply"), test::sample_sphere(600));
  const std::string common =
      "reconstruct '" + path("in.ply") + "' --target-edge 0.2 --quiet --seed 4 ";
  ASSERT_EQ(pdd(common + "-o '" + path("a.ply") + "' --stats '" + path("a.json") + "'").code, 0);
  ASSERT_EQ(pdd(common + "-o '" + path("b.ply") + "' --stats '" + path("b.json") +
                "' --no-cleanup")
                .code,
            0);
  // The flips of the final iteration, the last "cleanup_flips" in the JSON.
  auto final_flips = [&](const std::string& file) {
    const std::string json = slurp(path(file));
    const std::string key = "\"cleanup_flips\": ";
    return std::stoi(json.substr(json.rfind(key) + key.size()));
  };
  EXPECT_GT(final_flips("a.json"), 0);
  EXPECT_EQ(final_flips("b.json"), 0);
  const TriangleQuality a = triangle_quality(read_mesh(path("a.ply")));
  const TriangleQuality b = triangle_quality(read_mesh(path("b.ply")));
  EXPECT_GT(a.mean_min_angle, b.mean_min_angle);
  EXPECT_LE(a.fraction_below_20, b.fraction_below_20);
}

TEST_F(CliTest, BadOptionValuesExitTwoLeavingNoFile) {
  write_points(path("in.ply"), test::sample_sphere(100));
  const std::vector<std::string> options = {"--solver octree", "--domain grid", "--target-edge -1",
                                            "--iterations 0", "--linear lu",
                                            "--hole-coarsening 0.5", "--min-component-size -2",
                                            "--stats '" + path("s.txt") + "'",
                                            "--max-memory lots", "--max-memory 0",
                                            "--max-memory -2G", "--max-memory 8X",
                                            "--max-memory 1M"};
  for (const std::string& option : options) {
    const Outcome run =
        pdd("reconstruct '" + path("in.ply") + "' -o '" + path("out.ply") + "' " + option);
    EXPECT_EQ(run.code, 2) << option << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << option << ": " << run.err;
    if (option.rfind("--max-memory", 0) == 0) {
      EXPECT_NE(run.err.find("--max-memory"), std::string::npos) << run.err;
    }
    EXPECT_EQ(entries(), std::vector<std::string>{"in.ply"}) << option;
  }
}

TEST_F(CliTest, OptionsOutOfReachStateTheirBound) {
  write_points(path("in.ply"), test::sample_sphere(100));
  const std::string run_on =
      "reconstruct " + quoted_path("in.ply") + " -o " + quoted_path("out.ply") + " --quiet ";
  expect_refused({
      {run_on + "--enlarge-ratio 1e300",
       "--enlarge-ratio: must be a number > 1 and <= 100, got '1e300'"},
      {run_on + "--radius-edge 0.3", "--radius-edge: must be a number >= 1, got '0.3'"},
      {run_on + "--threads 1024", "--threads: must be an integer from 0 to "},
      {run_on + "--sphere-points 4",
       "initial domain: the hull of 4 points on the domain sphere (--sphere-points) reaches"},
      {run_on + "--sphere-points 8 --enlarge-ratio 1.2", "use more points or a ratio above"},
  });
  EXPECT_EQ(entries(), std::vector<std::string>{"in.ply"});
  // The bounds themselves are reachable: 4 sphere points enclose the input at a ratio of 5.
  const Outcome bounds =
      pdd("reconstruct " + quoted_path("in.ply") + " -o " + quoted_path("out.ply") +
          " --quiet --target-edge 0.4 --sphere-points 4 --enlarge-ratio 5 --radius-edge 1");
  EXPECT_EQ(bounds.code, 0) << bounds.err;
}

// A binary PLY whose header declares more records than its bytes can hold
// once made every command walk them for ever.
TEST_F(CliTest, HeaderCountsNoFileHoldsFailAtOnce) {
  write_mesh(path("mesh.ply"), tetrahedron());
  write_points(path("points.ply"), test::sample_sphere(100));
  // The same files with an element of empty records declared before the body.
  for (const std::string name : {"mesh.ply", "points.ply"}) {
    std::string text = slurp(path(name));
    text.insert(text.find("end_header\n"), "element junk 9000000000000000000\n");
    write_file("junk_" + name, text);
  }
  const std::string points = path("junk_points.ply"), mesh = path("junk_mesh.ply");
  const std::string junk =
      ": malformed header: element 'junk' declares 9000000000000000000 records but no properties";
  expect_refused({
      {"reconstruct '" + points + "' -o " + quoted_path("out.ply"), points + ": line 11" + junk},
      {"quality '" + mesh + "'", mesh + ": line 10" + junk},
      {"compare '" + mesh + "' " + quoted_path("mesh.ply"), mesh + ": line 10" + junk},
      {"compare " + quoted_path("mesh.ply") + " '" + mesh + "'", mesh + ": line 10" + junk},
  });
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

// A named pipe, a folder or a device as input is refused at once; opening a
// pipe once waited for a writer for ever.
TEST_F(CliTest, InputsThatAreNotRegularFilesAreRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo(path("pipe.ply").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo(path("pipe.xyz").c_str(), 0600), 0);
  fs::create_directory(path("folder.off"));
  write_mesh(path("mesh.ply"), tetrahedron());
  const std::string pipe = "pdd: error: " + path("pipe.ply") + ": not a regular file (a named pipe)";
  expect_refused({
      {"reconstruct " + quoted_path("pipe.ply") + " -o " + quoted_path("out.ply"), pipe},
      {"reconstruct " + quoted_path("pipe.xyz") + " -o " + quoted_path("out.ply"),
       "pdd: error: " + path("pipe.xyz") + ": not a regular file (a named pipe)"},
      {"quality " + quoted_path("pipe.ply"), pipe},
      {"compare " + quoted_path("mesh.ply") + " " + quoted_path("pipe.ply"), pipe},
      {"quality " + quoted_path("folder.off"),
       "pdd: error: " + path("folder.off") + ": is a folder, not a file"},
  });
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

TEST_F(CliTest, NoOutputReplacesTheInput) {
  write_points(path("in.ply"), test::sample_sphere(100));
  const std::string before = slurp(path("in.ply"));
  fs::create_directory(path("sub"));
  fs::create_symlink(path("in.ply"), path("soft.ply"));
  fs::create_hard_link(path("in.ply"), path("hard.ply"));
  fs::create_symlink(path("in.ply"), path("stats.json"));
  fs::create_symlink(path("in.ply"), path("domain.vtu"));
  const std::string run_on = "reconstruct " + quoted_path("in.ply") + " -o ";
  const std::string is_input =
      ": cannot write: it is the input file " + path("in.ply") + "; pdd does not overwrite it\n";
  Cases cases;
  for (const char* alias : {"in.ply", "./in.ply", "sub/../in.ply", "soft.ply", "hard.ply"})
    cases.emplace_back(run_on + quoted_path(alias), "pdd: error: " + path(alias) + is_input);
  cases.emplace_back(run_on + quoted_path("out.ply") + " --stats " + quoted_path("stats.json"),
                     path("stats.json") + is_input);
  cases.emplace_back(run_on + quoted_path("out.ply") + " --domain-out " + quoted_path("domain.vtu"),
                     path("domain.vtu") + is_input);
  expect_refused(cases);
  EXPECT_EQ(slurp(path("in.ply")), before);
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

TEST_F(CliTest, EveryOutputIsCheckedBeforeTheRun) {
  // The input does not exist: each output's problem is reported first.
  const std::string run_on = "reconstruct " + quoted_path("absent.ply") + " -o ";
  write_file("file", "x");
  const std::string long_name = std::string(300, 'n');
  expect_refused({
      {run_on + quoted_path(long_name + ".ply"),
       "a name in it is 304 bytes long, more than the 255"},
      {run_on + quoted_path("out.ply") + " --stats " + quoted_path(long_name + ".json"),
       "a name in it is 305 bytes long"},
      {run_on + quoted_path("out.ply") + " --domain-out " + quoted_path("file/d.vtu"),
       path("file") + "' is not a folder"},
      {run_on + quoted_path("out.ply") + " --save-iterations " + quoted_path("file"),
       path("file") + ": cannot write: it is a regular file, not a folder"},
      {run_on + quoted_path("out.ply") + " --save-iterations " + quoted_path("file/steps"),
       path("file/steps") + ": cannot write: cannot reach it: Not a directory"},
  });
  EXPECT_EQ(entries(), std::vector<std::string>{"file"});
}

// A folder where no file can be created although its permissions say so (as
// root, or under /proc): found before the run, nothing written.
TEST_F(CliTest, AnOutputThatCannotBeCreatedFailsBeforeTheRun) {
  write_points(path("in.ply"), test::sample_sphere(300));
  const Outcome run = pdd("reconstruct " + quoted_path("in.ply") + " -o " +
                          quoted_path("out.ply") + " --domain-out " + quoted_path("d.vtu") +
                          " --stats /proc/pdd_stats.json");
  EXPECT_EQ(run.code, 2) << run.err;
  EXPECT_EQ(run.err.find("iteration"), std::string::npos) << "the run started: " << run.err;
  EXPECT_EQ(lines_of(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find("/proc/pdd_stats.json: cannot write: the folder '/proc' is not writable"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"in.ply"});
}

// Measures that would come out as NaN or infinite fail instead, naming the file.
TEST_F(CliTest, ReportsNeverShowNanOrOverflow) {
  write_mesh(path("t.ply"), tetrahedron());
  TriangleMesh far = tetrahedron();
  far.vertices[3] = Vec3(0, 0, -1e308);
  write_mesh(path("far.ply"), far);
  TriangleMesh scaled = tetrahedron();
  for (Vec3& v : scaled.vertices) v *= 1e200;
  write_mesh(path("scaled.off"), scaled);
  const Cases cases = {
      {"compare " + quoted_path("far.ply") + " " + quoted_path("t.ply"),
       path("far.ply") + ": the vertices span 1e+308 (bounding-box diagonal), more than the 1e+150"},
      {"compare --json " + quoted_path("t.ply") + " " + quoted_path("far.ply"),
       path("far.ply") + ": the vertices span"},
      {"quality " + quoted_path("scaled.off"),
       path("scaled.off") + ": the vertices span 1.73e+200"},
      {"quality --json " + quoted_path("scaled.off"), path("scaled.off")},
      {"compare --samples 1099511627776 " + quoted_path("t.ply") + " " + quoted_path("t.ply"),
       "--samples: Value 1099511627776 not in range 1 to 100000000"},
  };
  expect_refused(cases);
  for (const auto& [command, message] : cases) EXPECT_EQ(pdd(command).out, "") << command;
  const Outcome fine = pdd("quality --json " + quoted_path("t.ply"));
  EXPECT_EQ(fine.code, 0) << fine.err;
  EXPECT_EQ(fine.out.find("null"), std::string::npos) << fine.out;
}

// The kitten scan in UTM-like coordinates reconstructs as it does at the origin.
TEST_F(CliTest, GeoreferencedCoordinatesAreAccepted) {
  PointSet kitten = read_points(std::string(PDD_SOURCE_DIR) + "/data/kitten_scan.ply");
  for (Vec3& p : kitten.points) p += Vec3(5e5, 5e6, 0);
  write_points(path("utm.ply"), kitten);
  const Outcome run = pdd("reconstruct " + quoted_path("utm.ply") + " -o " +
                          quoted_path("out.ply") + " --quiet --target-edge 0.1");
  ASSERT_EQ(run.code, 0) << run.err;
  const TriangleMesh mesh = read_mesh(path("out.ply"));
  EXPECT_GT(mesh.faces.size(), 100u);
  for (const Vec3& v : mesh.vertices) {
    EXPECT_NEAR(v.x(), 5e5, 2);
    EXPECT_NEAR(v.y(), 5e6, 2);
  }
}

TEST_F(CliTest, ColoursTrimAndOutliersOnTheCommandLine) {
  PointSet sphere = test::sample_sphere(1500);
  Attribute red{"red", "uchar", {}}, green{"green", "uchar", {}}, blue{"blue", "uchar", {}};
  for (const Vec3& p : sphere.points) {
    red.values.push_back(std::round(127.5 * (p.z() + 1)));
    green.values.push_back(10);
    blue.values.push_back(20);
  }
  sphere.attributes = {red, green, blue};
  write_points(path("c.ply"), sphere);
  const Outcome run = pdd("reconstruct " + quoted_path("c.ply") + " -o " + quoted_path("out.ply") +
                          " --quiet --target-edge 0.15 --stats " + quoted_path("s.json"));
  ASSERT_EQ(run.code, 0) << run.err;
  const TriangleMesh mesh = read_mesh(path("out.ply"));
  ASSERT_EQ(mesh.attributes.size(), 3u);
  EXPECT_EQ(mesh.attributes[0].name, "red");
  EXPECT_EQ(mesh.attributes[0].type, "uchar");
  EXPECT_EQ(mesh.attributes[1].values[0], 10);
  const std::string stats = slurp(path("s.json"));
  EXPECT_NE(stats.find("\"attributes\": [\"red\", \"green\", \"blue\"]"), std::string::npos);
  EXPECT_NE(stats.find("\"outliers\": {\"ratio\": 3"), std::string::npos) << stats;
  EXPECT_NE(stats.find("\"trim\": {\"trimmed\": false"), std::string::npos) << stats;

  // Bad values: one line, exit 2, no output.
  fs::remove(path("out.ply"));
  fs::remove(path("s.json"));
  const std::string again = "reconstruct " + quoted_path("c.ply") + " -o " + quoted_path("out.ply");
  expect_refused({{again + " --trim -1", "--trim: must be a number >= 0 and <= 100, got '-1'"},
                  {again + " --trim 101", "--trim: must be"},
                  {again + " --trim-holes x", "--trim-holes: must be"},
                  {again + " --outliers -3", "--outliers: must be"},
                  {again + " --attributes 'red;blue'", "--attributes: must be colors, all, none"},
                  {again + " --attributes intensity",
                   "the points have no property 'intensity' (they have red, green, blue)"}});
  write_file("bad.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
             "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
             "end_header\n0 0 0 0 0 0\n1 0 0 0 0 0\n0 1 0 2 0 0\n0 0 1 0 0 0\n");
  expect_refused({{"reconstruct " + quoted_path("bad.ply") + " -o " + quoted_path("out.ply"),
                   "line 13 (point 3): the colour property 'red' is 2, outside 0-1"}});
  EXPECT_FALSE(fs::exists(path("out.ply")));
  EXPECT_FALSE(fs::exists(path("s.json")));
}

}  // namespace
}  // namespace pdd
