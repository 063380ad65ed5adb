// facet — files written whole or not at all.
#pragma once

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace facet {

class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `content` to a temporary file beside `path`, then renames it over
// `path`: readers see the old file or the new one, never a part. On failure
// the temporary file is removed, `path` is untouched, and IoError names it.
void write_file_atomic(const std::string& path, const std::string& content);
// The same for a file too big to hold: `write` streams it into the temporary file.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write);
std::string read_file(const std::string& path);  // IoError when unreadable

}  // namespace facet
