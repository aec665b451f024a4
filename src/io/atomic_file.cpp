// Atomic output: every writer streams into a fresh temporary file next to the
// target and renames it over the target only once everything is written and
// flushed, so a failed run never leaves a partial or empty file. POSIX calls
// are used directly (open with O_EXCL, write, fsync, rename) because the
// standard streams neither create a file exclusively nor report errno.
#include <fcntl.h>
#include <pdd/io.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <streambuf>

#include "io/text.h"

namespace pdd {

namespace {

namespace fs = std::filesystem;

// A write-only stream buffer on a file descriptor that remembers the first
// errno a write met.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof(buffer_)); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t written = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) {
        if (error_ == 0) error_ = written < 0 ? errno : EIO;
        return false;
      }
      p += written;
    }
    setp(buffer_, buffer_ + sizeof(buffer_));
    return true;
  }

  int fd_;
  int error_ = 0;
  char buffer_[1 << 16];
};

fs::path folder_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// Why a file cannot be created in `path`'s folder, or "" when it can.
std::string folder_problem(const std::string& path) {
  const fs::path folder = folder_of(path);
  std::error_code ec;
  const auto status = fs::status(folder, ec);
  if (status.type() == fs::file_type::not_found) {
    return "the folder '" + folder.string() + "' does not exist";
  }
  if (status.type() != fs::file_type::directory) {
    return "'" + folder.string() + "' is not a folder";
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    return "the folder '" + folder.string() + "' is not writable (" + std::strerror(errno) + ")";
  }
  if (fs::is_directory(fs::status(path, ec))) return "it is a folder";
  return "";
}

// Creates a new, empty temporary file next to `path`; returns its descriptor.
int create_temporary(const std::string& path, std::string& temporary) {
  static std::atomic<unsigned> counter{0};
  const fs::path target(path);
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = (folder_of(path) / ("." + target.filename().string() + ".tmp-" +
                                    std::to_string(::getpid()) + "-" + std::to_string(counter++)))
                    .string();
    // 0666 minus the umask: the final file gets the usual permissions.
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno == EEXIST) continue;
    const int error = errno;
    const std::string problem = folder_problem(path);
    io::fail(path, "cannot write: " + (problem.empty() ? std::strerror(error) : problem));
  }
  io::fail(path, "cannot write: no free name for a temporary file");
}

}  // namespace

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  if (fs::is_directory(path)) io::fail(path, "cannot write: it is a folder");
  std::string temporary;
  int fd = create_temporary(path, temporary);
  try {
    FdBuffer buffer(fd);
    std::ostream out(&buffer);
    write(out);
    out.flush();
    if (!out || buffer.error() != 0) {
      throw std::runtime_error(
          path + ": cannot write: " + std::strerror(buffer.error() ? buffer.error() : EIO));
    }
    if (::fsync(fd) != 0) {
      throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
    }
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
      throw std::runtime_error(
          path + ": cannot rename the temporary file onto it: " + std::strerror(errno));
    }
  } catch (...) {
    if (fd >= 0) ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
}

void check_output_path(const std::string& path, OutputKind kind) {
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
  }
  const std::string problem = folder_problem(path);
  if (!problem.empty()) io::fail(path, "cannot write: " + problem);
}

}  // namespace pdd
