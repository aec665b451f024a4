#include "io/text.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pdd::io {

namespace {

struct FormatName {
  const char* extension;
  Format format;
};

constexpr FormatName kExtensions[] = {
    {".ply", Format::kPly}, {".xyz", Format::kXyz}, {".pwn", Format::kXyz}, {".xyzn", Format::kXyz},
    {".off", Format::kOff}, {".obj", Format::kObj}, {".vtu", Format::kVtu},
    {".json", Format::kJson},
};

std::string lowercase(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

}  // namespace

Format format_of(const std::string& path, const std::vector<Format>& allowed,
                 const std::string& what) {
  const std::string extension = lowercase(std::filesystem::path(path).extension().string());
  std::string expected;
  for (const FormatName& name : kExtensions) {
    bool ok = false;
    for (Format f : allowed) ok = ok || f == name.format;
    if (!ok) continue;
    if (extension == name.extension) return name.format;
    expected += (expected.empty() ? "" : " ") + std::string(name.extension);
  }
  if (extension.empty()) {
    fail(path, "no file extension; a " + what + " file must end in one of " + expected);
  }
  fail(path, "unknown extension " + quote(extension) + " for a " + what + " file; expected one of " +
                 expected);
}

std::string load_file(const std::string& path) {
  // O_NONBLOCK: opening a named pipe would otherwise wait for a writer;
  // fstat then refuses anything but a regular file before a byte is read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) fail(path, "no such file");
    fail(path, std::string("cannot open: ") + std::strerror(errno));
  }
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat status {};
  if (::fstat(fd, &status) != 0) fail(path, std::string("cannot read: ") + std::strerror(errno));
  if (S_ISDIR(status.st_mode)) fail(path, "is a folder, not a file");
  if (!S_ISREG(status.st_mode))
    fail(path, std::string("not a regular file (") + file_kind(status.st_mode) + ")");
  // One byte more than its size, so that the read that meets the end needs no
  // reallocation; more when the file grows meanwhile.
  std::string content(static_cast<std::size_t>(status.st_size) + 1, '\0');
  std::size_t filled = 0;
  while (true) {
    if (filled == content.size()) content.resize(2 * content.size());
    const ssize_t n = ::read(fd, content.data() + filled, content.size() - filled);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;
    filled += static_cast<std::size_t>(n);
  }
  content.resize(filled);
  return content;
}

const char* file_kind(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "a special file";
}

void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": " + what);
}

void fail_at_line(const std::string& path, std::size_t line, const std::string& what) {
  throw InputError(path + ": line " + std::to_string(line) + ": " + what);
}

LineReader::LineReader(std::string_view text, char comment, std::size_t first_line)
    : text_(text), comment_(comment), next_line_(first_line) {}

bool LineReader::next(std::vector<std::string_view>& tokens) {
  tokens.clear();
  while (pos_ < text_.size()) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view content = text_.substr(pos_, end - pos_);
    pos_ = end < text_.size() ? end + 1 : end;
    line_ = next_line_++;
    if (comment_ != '\0') content = content.substr(0, content.find(comment_));
    std::size_t i = 0;
    while (i < content.size()) {
      while (i < content.size() && std::isspace(static_cast<unsigned char>(content[i]))) ++i;
      const std::size_t start = i;
      while (i < content.size() && !std::isspace(static_cast<unsigned char>(content[i]))) ++i;
      if (i > start) tokens.push_back(content.substr(start, i - start));
    }
    if (!tokens.empty()) return true;
  }
  return false;
}

bool parse_double(std::string_view token, double& value) {
  // std::from_chars is exact, locale-free and reads "nan"/"inf"; it does not
  // take a leading '+', which text files sometimes carry.
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

bool parse_integer(std::string_view token, std::int64_t& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

double double_at(std::string_view token, const std::string& path, std::size_t line) {
  double value;
  if (!parse_double(token, value)) {
    fail_at_line(path, line, quote(token) + " is not a number");
  }
  return value;
}

std::int64_t integer_at(std::string_view token, const std::string& path, std::size_t line) {
  std::int64_t value;
  if (!parse_integer(token, value)) {
    fail_at_line(path, line, quote(token) + " is not an integer");
  }
  return value;
}

void append_double(std::string& out, double value) {
  char buffer[32];
  // Without a precision, std::to_chars writes the shortest text that reads
  // back to the same double: exact round trips with no trailing noise.
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

std::string format_double(double value) {
  std::string s;
  append_double(s, value);
  return s;
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace pdd::io
