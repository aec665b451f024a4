// Shared by the readers and writers of src/io: loading a file, naming its
// format, splitting text into numbered lines of tokens, parsing and printing
// numbers exactly, and phrasing errors as "<path>: line <n>: <what>".
#pragma once

#include <pdd/errors.h>
#include <sys/types.h>

#include "common/quote.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pdd::io {

enum class Format { kPly, kXyz, kOff, kObj, kVtu, kJson };

// The format named by the path's extension (case-insensitive). `allowed`
// lists the formats the caller handles and `what` names what the file holds
// ("point set", "mesh", ...) for the message; any other extension throws
// InputError.
Format format_of(const std::string& path, const std::vector<Format>& allowed,
                 const std::string& what);

// The whole file. Throws InputError when it is missing, unreadable or not a
// regular file (a folder, a named pipe, a device), without waiting on a pipe.
std::string load_file(const std::string& path);

// What a file of this st_mode is, for messages: "a named pipe", "a folder", ...
const char* file_kind(mode_t mode);

// "<path>: <what>" and "<path>: line <n>: <what>" as InputError.
[[noreturn]] void fail(const std::string& path, const std::string& what);
[[noreturn]] void fail_at_line(const std::string& path, std::size_t line, const std::string& what);

// Splits text into lines (LF or CRLF) and lines into whitespace-separated
// tokens, numbering lines from `first_line`. Text after `comment` (when not
// '\0') is ignored, as are lines left blank.
class LineReader {
 public:
  LineReader(std::string_view text, char comment, std::size_t first_line = 1);
  // The tokens of the next non-blank line; false at the end of the text.
  bool next(std::vector<std::string_view>& tokens);
  // Number of the line last returned by next().
  std::size_t line() const { return line_; }
  // Byte offset just past the line last returned by next().
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  std::size_t next_line_;
};

// Parses the whole token as a double ("nan" and "inf" included, so that
// validation can name them) or as an integer. False when it is not one.
bool parse_double(std::string_view token, double& value);
bool parse_integer(std::string_view token, std::int64_t& value);

// Parses a double or an integer at a numbered line, throwing InputError
// "<path>: line <n>: '<token>' is not a number" on failure.
double double_at(std::string_view token, const std::string& path, std::size_t line);
std::int64_t integer_at(std::string_view token, const std::string& path, std::size_t line);

// Appends the shortest decimal text that reads back to exactly `value`.
void append_double(std::string& out, double value);
// The same as a string, for messages.
std::string format_double(double value);

// True on little-endian machines; the binary formats convert when needed.
bool host_is_little_endian();

}  // namespace pdd::io
