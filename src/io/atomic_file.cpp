// Atomic output: every writer streams into a fresh temporary file next to the
// target and renames it over the target only once everything is written and
// flushed (StagedOutputs: once every output of a run is), so a failed run
// never leaves a partial or empty file. POSIX calls
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

#include "io/formats.h"
#include "io/output_paths.h"
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

// Creates a new, empty temporary file next to `path`; returns its descriptor.
// Its name is the target's with a dot before and a suffix after, or a short
// one when that would be longer than the file system allows.
int create_temporary(const std::string& path, std::string& temporary) {
  static std::atomic<unsigned> counter{0};
  const fs::path folder = io::folder_of(path);
  const std::string name = fs::path(path).filename().string();
  const std::size_t name_max = io::name_max(folder);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string suffix = ".tmp-" + std::to_string(::getpid()) + "-" +
                               std::to_string(counter++);
    const std::string long_name = "." + name + suffix;
    temporary = (folder / (long_name.size() <= name_max ? long_name : ".pdd" + suffix)).string();
    // 0666 minus the umask: the final file gets the usual permissions.
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno == EEXIST) continue;
    const int error = errno;
    const std::string problem = io::target_problem(path);
    io::fail(path, "cannot write: " + (problem.empty() ? std::strerror(error) : problem));
  }
  io::fail(path, "cannot write: no free name for a temporary file");
}

// Writes into a new temporary next to `path` and returns its name, flushed
// and closed; removes it and throws on any failure.
std::string write_temporary(const std::string& path,
                            const std::function<void(std::ostream&)>& write) {
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
  } catch (...) {
    if (fd >= 0) ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
  return temporary;
}

}  // namespace

StagedOutputs::~StagedOutputs() { discard(); }

void StagedOutputs::discard() {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Staged& s : staged_) ::unlink(s.temporary.c_str());
  for (auto f = created_folders_.rbegin(); f != created_folders_.rend(); ++f) ::rmdir(f->c_str());
  staged_.clear();
  created_folders_.clear();
}

void StagedOutputs::create_folder(const std::string& folder) {
  std::vector<std::string> missing;
  for (std::filesystem::path p = folder; !p.empty() && !std::filesystem::exists(p);
       p = p.parent_path()) {
    missing.push_back(p.string());
    if (p == p.parent_path()) break;
  }
  std::filesystem::create_directories(folder);
  const std::lock_guard<std::mutex> lock(mutex_);
  created_folders_.insert(created_folders_.end(), missing.rbegin(), missing.rend());
}

void StagedOutputs::add(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = write_temporary(path, write);
  const std::lock_guard<std::mutex> lock(mutex_);
  staged_.push_back({path, temporary});
}

void StagedOutputs::commit() {
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    if (::rename(staged_[i].temporary.c_str(), staged_[i].path.c_str()) == 0) continue;
    const int error = errno;
    // None of the outputs stays: those renamed already go, the destructor
    // removes the other temporaries.
    for (std::size_t k = 0; k < i; ++k) ::unlink(staged_[k].path.c_str());
    const std::string path = staged_[i].path;
    staged_.erase(staged_.begin(), staged_.begin() + static_cast<std::ptrdiff_t>(i));
    throw std::runtime_error(path + ": cannot rename the temporary file onto it: " +
                             std::strerror(error));
  }
  staged_.clear();
  created_folders_.clear();
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  StagedOutputs output;
  output.add(path, write);
  output.commit();
}

void io::write_output(const std::string& path, StagedOutputs* staged,
                      const std::function<void(std::ostream&)>& write) {
  if (staged) {
    staged->add(path, write);
  } else {
    write_atomically(path, write);
  }
}

}  // namespace pdd
