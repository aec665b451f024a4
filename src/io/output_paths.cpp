// Output paths checked before a run: the extension, the folder, the name's
// length and the file already there, so that a run never fails at its end for
// a reason known at its start, and never overwrites its input.
#include "io/output_paths.h"

#include <fcntl.h>
#include <pdd/io.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>

#include "io/text.h"

namespace pdd::io {

namespace fs = std::filesystem;

namespace {

// Why `path`, a name the kernel will be given, is too long, or "".
std::string length_problem(const std::string& path, const fs::path& folder) {
  if (path.size() >= PATH_MAX) {
    return "the path is " + std::to_string(path.size()) + " bytes long, more than the " +
           std::to_string(PATH_MAX - 1) + " the system allows";
  }
  const std::size_t longest = name_max(folder);
  for (const fs::path& part : fs::path(path)) {
    const std::size_t size = part.string().size();
    if (size > longest) {
      return "a name in it is " + std::to_string(size) + " bytes long, more than the " +
             std::to_string(longest) + " the file system allows";
    }
  }
  return "";
}

// Why no file can be created in `folder`, or "".
std::string folder_problem(const fs::path& folder) {
  struct stat status {};
  if (::stat(folder.c_str(), &status) != 0) {
    if (errno == ENOENT) return "the folder '" + folder.string() + "' does not exist";
    return "cannot reach the folder '" + folder.string() + "': " + std::strerror(errno);
  }
  if (!S_ISDIR(status.st_mode)) return "'" + folder.string() + "' is not a folder";
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    return "the folder '" + folder.string() + "' is not writable (" + std::strerror(errno) + ")";
  }
  return "";
}

// Why no file can be created in `folder` after all, or "": a file is created
// there and removed, since permissions do not tell (root passes them; /proc
// and read-only mounts refuse anyway).
std::string probe_problem(const fs::path& folder) {
  const fs::path probe = folder / (".pdd-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0 && errno != EEXIST) {
    return "the folder '" + folder.string() + "' is not writable (" + std::strerror(errno) + ")";
  }
  if (fd >= 0) {
    ::close(fd);
    ::unlink(probe.c_str());
  }
  return "";
}

// Why `path` cannot be used as the folder of --save-iterations (created with
// its missing parents), or "".
std::string iterations_folder_problem(const std::string& path) {
  if (const std::string problem = length_problem(path, folder_of(path)); !problem.empty())
    return problem;
  fs::path existing = fs::path(path);
  while (true) {
    struct stat status {};
    if (::stat(existing.c_str(), &status) == 0) {
      if (existing == fs::path(path) && !S_ISDIR(status.st_mode))
        return std::string("it is ") + file_kind(status.st_mode) + ", not a folder";
      break;
    }
    if (errno != ENOENT) return "cannot reach it: " + std::string(std::strerror(errno));
    existing = existing.parent_path();
    if (existing.empty()) {
      existing = ".";
      break;
    }
  }
  if (const std::string problem = folder_problem(existing); !problem.empty()) return problem;
  return probe_problem(existing);
}

}  // namespace

fs::path folder_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

std::size_t name_max(const fs::path& folder) {
  const long limit = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  return limit > 0 ? static_cast<std::size_t>(limit) : NAME_MAX;
}

std::string target_problem(const std::string& path) {
  const fs::path folder = folder_of(path);
  if (const std::string problem = length_problem(path, folder); !problem.empty()) return problem;
  if (const std::string problem = folder_problem(folder); !problem.empty()) return problem;
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return "";
  if (S_ISDIR(status.st_mode)) return "it is a folder";
  if (!S_ISREG(status.st_mode))
    return std::string("it is ") + file_kind(status.st_mode) + ", not a regular file";
  return "";
}

}  // namespace pdd::io

namespace pdd {

void check_output_path(const std::string& path, OutputKind kind,
                       const std::vector<std::string>& inputs) {
  switch (kind) {
    case OutputKind::kMesh:
      io::format_of(path, {io::Format::kPly, io::Format::kOff, io::Format::kObj}, "mesh");
      break;
    case OutputKind::kPoints:
      io::format_of(path, {io::Format::kPly, io::Format::kXyz, io::Format::kOff, io::Format::kObj},
                    "point set");
      break;
    case OutputKind::kDomain:
      io::format_of(path, {io::Format::kVtu}, "domain");
      break;
    case OutputKind::kStatistics:
      io::format_of(path, {io::Format::kJson}, "statistics");
      break;
    case OutputKind::kFolder:
      break;
  }
  std::string problem =
      kind == OutputKind::kFolder ? io::iterations_folder_problem(path) : io::target_problem(path);
  if (problem.empty() && kind != OutputKind::kFolder) problem = io::probe_problem(io::folder_of(path));
  if (!problem.empty()) io::fail(path, "cannot write: " + problem);
  // The same file under another name, or through a symbolic or hard link.
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (std::filesystem::equivalent(input, path, ec) && !ec)
      io::fail(path, "cannot write: it is the input file " + input + "; pdd does not overwrite it");
  }
}

}  // namespace pdd
