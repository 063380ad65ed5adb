#include "core/diagnostics.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/io.h"

namespace facet {

using nlohmann::json;

std::string Diagnostic::format() const {
  std::string where = file;
  if (line > 0) where += fmt::format(":{}:{}", line, column);
  return fmt::format("{}: {}: {}", where, path.empty() ? "(document)" : path, message);
}

namespace {
std::string join_messages(const std::vector<Diagnostic>& ds) {
  std::string s;
  for (const auto& d : ds) s += (s.empty() ? "" : "\n") + d.format();
  return s;
}
}  // namespace

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join_messages(diagnostics)), diagnostics_(std::move(diagnostics)) {}

DiagnosticSink::DiagnosticSink(std::string file, std::string folder) : file_(std::move(file)), folder_(std::move(folder)) {
  if (folder_.empty()) folder_ = std::filesystem::path(file_).parent_path().string();
}

void DiagnosticSink::error(const std::string& path, const std::string& message) {
  diagnostics_.push_back({file_, path, message, 0, 0});
}

void DiagnosticSink::throw_if_any() const {
  if (!diagnostics_.empty()) throw InputError(diagnostics_);
}

namespace {
std::function<void(const std::string&)>& progress_sink() {
  static std::function<void(const std::string&)> sink;
  return sink;
}
}  // namespace

void set_progress_sink(std::function<void(const std::string&)> sink) { progress_sink() = std::move(sink); }

void progress(const std::string& line) {
  if (progress_sink()) progress_sink()(line);
}

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string index_path(const std::string& parent, size_t index) {
  return fmt::format("{}[{}]", parent, index);
}

std::string json_type_name(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "a value";
  }
}

std::string suggest(const std::string& word, const std::vector<std::string>& candidates) {
  auto distance = [](const std::string& a, const std::string& b) {
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      cur[0] = i;
      for (size_t j = 1; j <= b.size(); ++j)
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
      std::swap(prev, cur);
    }
    return prev[b.size()];
  };
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    size_t d = distance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

namespace {

// nlohmann's DOM builder, plus the key path the parser is at (for syntax
// errors) and a check for duplicate keys, which JSON parsers otherwise
// resolve silently.
class TrackingSax {
 public:
  explicit TrackingSax(json& root) : dom_(root, /*allow_exceptions=*/false) {}

  bool null() { return value() && dom_.null() && done(); }
  bool boolean(bool v) { return value() && dom_.boolean(v) && done(); }
  bool number_integer(json::number_integer_t v) { return value() && dom_.number_integer(v) && done(); }
  bool number_unsigned(json::number_unsigned_t v) { return value() && dom_.number_unsigned(v) && done(); }
  bool number_float(json::number_float_t v, const std::string& s) { return value() && dom_.number_float(v, s) && done(); }
  bool string(std::string& v) { return value() && dom_.string(v) && done(); }
  bool binary(json::binary_t& v) { return value() && dom_.binary(v) && done(); }
  bool start_object(size_t n) {
    if (!value()) return false;
    if (frames_.size() >= kMaxJsonDepth) {
      too_deep_ = true;
      return false;
    }
    frames_.push_back({false, "", 0, {}});
    return dom_.start_object(n);
  }
  bool key(std::string& k) {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      duplicate_ = join_path(path(frames_.size() - 1), k);
      return false;
    }
    f.key = k;
    f.has_key = true;
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object() && done();
  }
  bool start_array(size_t n) {
    if (!value()) return false;
    if (frames_.size() >= kMaxJsonDepth) {
      too_deep_ = true;
      return false;
    }
    frames_.push_back({true, "", 0, {}});
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array() && done();
  }
  template <class Exception>
  bool parse_error(size_t position, const std::string& token, const Exception& ex) {
    error_position_ = position;
    error_token_ = token;
    error_what_ = ex.what();
    return false;
  }

  // Where the parser was: the path of the value being read.
  std::string path(size_t depth) const {
    std::string p;
    for (size_t i = 0; i < depth; ++i) {
      const Frame& f = frames_[i];
      if (f.array) p = index_path(p, f.count == 0 ? 0 : f.count - 1);
      else if (f.has_key) p = join_path(p, f.key);
    }
    return p;
  }
  size_t depth() const { return frames_.size(); }
  std::string current_path() const {
    // Within an array the next element is at index `count`.
    std::string p;
    for (size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      bool last = i + 1 == frames_.size();
      if (f.array) p = index_path(p, last ? f.count : (f.count == 0 ? 0 : f.count - 1));
      else if (f.has_key) p = join_path(p, f.key);
    }
    return p;
  }

  std::string duplicate_;
  bool too_deep_ = false;
  size_t error_position_ = 0;
  std::string error_token_;
  std::string error_what_;

 private:
  struct Frame {
    bool array;
    std::string key;
    size_t count;
    std::set<std::string> keys;
    bool has_key = false;
  };
  // A value is complete: within an object, the next error is no longer at its key.
  bool done() {
    if (!frames_.empty() && !frames_.back().array) frames_.back().has_key = false;
    return true;
  }
  // Counts array elements as they start, so paths name the element being read.
  bool value() {
    if (!frames_.empty() && frames_.back().array) frames_.back().count++;
    return true;
  }
  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::vector<Frame> frames_;
};

void line_column(const std::string& text, size_t position, int& line, int& column) {
  line = 1;
  column = 1;
  for (size_t i = 0; i < position && i < text.size(); ++i) {
    if (text[i] == '\n') ++line, column = 1;
    else ++column;
  }
}

// nlohmann's messages start with "[json.exception.parse_error.101] parse error at line 1, column 5: ".
std::string plain_message(const std::string& what) {
  std::string s = what;
  if (auto p = s.find("] "); p != std::string::npos) s = s.substr(p + 2);
  if (auto p = s.find(": "); p != std::string::npos && s.rfind("parse error", 0) == 0) s = s.substr(p + 2);
  return s;
}

// Where an array or object opens kMaxJsonDepth + 1 levels deep (outside strings).
size_t too_deep_at(const std::string& text) {
  size_t depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return 0;
}

}  // namespace

json parse_json(const std::string& text, const std::string& file) {
  bool blank = std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); });
  if (blank) throw InputError({{file, "", "the file is empty; expected a JSON document", 1, 1}});
  json root;
  TrackingSax sax(root);
  bool ok = json::sax_parse(text, &sax, json::input_format_t::json, /*strict=*/true);
  if (ok) return root;
  Diagnostic d{file, "", "", 0, 0};
  if (!sax.duplicate_.empty()) {
    d.path = sax.duplicate_;
    d.message = "duplicate key; each key may appear once";
    throw InputError({d});
  }
  if (sax.too_deep_) {
    const std::string path = sax.path(sax.depth());  // the value that opened one level too many
    d.path = path.size() <= 100 ? path : path.substr(0, 60) + "…" + path.substr(path.size() - 30);
    line_column(text, too_deep_at(text), d.line, d.column);
    d.message = fmt::format("arrays and objects nest deeper here than the {} levels facet reads", kMaxJsonDepth);
    throw InputError({d});
  }
  // A syntax error: name the position and the key the parser was reading.
  size_t pos = sax.error_position_ > 0 ? sax.error_position_ - 1 : 0;
  line_column(text, pos, d.line, d.column);
  d.path = sax.current_path();
  d.message = "syntax error: " + plain_message(sax.error_what_);
  throw InputError({d});
}

json read_json_file(const std::string& path) {
  std::string text;
  try {
    text = read_file(path, kMaxDocumentBytes);
  } catch (const IoError& e) {  // the message begins with the path, which the diagnostic names
    const std::string what = e.what();
    throw InputError({{path, "", what.rfind(path + ": ", 0) == 0 ? what.substr(path.size() + 2) : what, 0, 0}});
  }
  // About 70 MB a second: a file this big takes a second or more (inline meshes).
  if (text.size() >= 64'000'000) progress(fmt::format("reading {}: {} MB of JSON", path, text.size() / 1'000'000));
  return parse_json(text, path);
}

}  // namespace facet
