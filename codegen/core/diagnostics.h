// facet — errors in user input, each naming the file and the key path.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace facet {

struct Diagnostic {
  std::string file;     // as the user named it
  std::string path;     // key path, e.g. specular.fresnel.f0[1]; "(document)" for the whole file
  std::string message;  // what is wrong, and what is allowed
  int line = 0;         // 1-based; 0 when unknown
  int column = 0;
  std::string format() const;  // file:line:col: path: message
};

// Thrown for bad input; carries every problem found, not just the first.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

// Collects diagnostics while a document is checked; throws them all at the end.
class DiagnosticSink {
 public:
  // `folder`: where the document's relative file names start, and the folder its files must
  // lie in (core/io.h, confined_path()); empty: the folder of `file`.
  explicit DiagnosticSink(std::string file, std::string folder = "");
  void error(const std::string& path, const std::string& message);
  bool empty() const { return diagnostics_.empty(); }
  void throw_if_any() const;
  const std::string& file() const { return file_; }
  const std::string& folder() const { return folder_; }

 private:
  std::string file_, folder_;
  std::vector<Diagnostic> diagnostics_;
};

// JSON text → document. Syntax errors name the line, column and the key path the
// parser had reached; duplicate keys and an empty document are errors too.
nlohmann::json parse_json(const std::string& text, const std::string& file);
// How deep parse_json() lets arrays and objects nest (README, "Reliability"): facet's files
// nest a dozen levels; tinygltf and the printers walk documents recursively, so a document
// nested thousands deep is refused before either sees it.
inline constexpr size_t kMaxJsonDepth = 256;
nlohmann::json read_json_file(const std::string& path);  // also reports a missing/unreadable file

// Progress of a step that takes seconds (reading a big mesh): one line, without
// its newline. The command line prints it on stderr; by default it goes nowhere.
void set_progress_sink(std::function<void(const std::string&)> sink);
void progress(const std::string& line);

// "a.b[2].c" helpers.
std::string join_path(const std::string& parent, const std::string& key);
std::string index_path(const std::string& parent, size_t index);
// Closest of `candidates` to `word` when it is a likely typo, else "".
std::string suggest(const std::string& word, const std::vector<std::string>& candidates);
// "number", "string", "array", … as a user reads them.
std::string json_type_name(const nlohmann::json& j);

}  // namespace facet
