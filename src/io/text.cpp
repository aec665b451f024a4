#include "io/text.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>

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
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) fail(path, "no such file");
  if (status.type() == std::filesystem::file_type::directory) fail(path, "is a folder, not a file");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  const std::streamoff size = in.tellg();
  if (size < 0) fail(path, std::string("cannot read: ") + std::strerror(errno));
  std::string content(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(content.data(), size))
    fail(path, std::string("cannot read: ") + std::strerror(errno));
  return content;
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
