// Small helpers shared by the readers and writers: whole-file loading, line iteration with line
// numbers, strict number parsing, and writing through a temporary file so that a failed write
// leaves no partial output.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace hexdom::io {

/// Whole file as bytes; throws InputError "path: cannot open file" when unreadable.
std::string load_file(const std::string& path);

/// Iterates over the lines of a buffer (LF or CRLF), counting from 1.
class LineCursor {
 public:
  LineCursor(const std::string& path, std::string_view text) : path_(path), text_(text) {}
  /// Next line without its line ending; false at the end.
  bool next(std::string_view& line);
  long line() const { return line_; }
  size_t offset() const { return pos_; }
  void seek(size_t offset, long line) { pos_ = offset; line_ = line; }
  const std::string& path() const { return path_; }
  /// Throws InputError at the current line.
  [[noreturn]] void fail(const std::string& text) const;

 private:
  std::string path_;
  std::string_view text_;
  size_t pos_ = 0;
  long line_ = 0;
};

std::string_view trim(std::string_view s);
/// Splits on runs of blanks (spaces, tabs).
std::vector<std::string_view> split_ws(std::string_view s);
/// Splits on commas, trimming each field.
std::vector<std::string_view> split_commas(std::string_view s);
std::string lower(std::string_view s);
bool starts_with_ci(std::string_view s, std::string_view prefix);

/// Parses the whole field as a finite double / an int; false on any other content.
bool parse_double(std::string_view s, double& out);
bool parse_int(std::string_view s, long& out);

/// File extension in lower case without the dot ("vtk"), "" when none.
std::string extension(const std::string& path);

/// Writes a file by calling `body` on a stream to a temporary file beside `path`, then renaming it.
/// If `body` throws, the temporary is removed and nothing is left at `path`. Throws InputError when
/// the file cannot be created or written.
void write_atomically(const std::string& path, bool binary,
                      const std::function<void(std::ostream&)>& body);

}  // namespace hexdom::io
