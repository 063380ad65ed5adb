// The cost rows' format (analysis/cost.h): what `facet cost --json` prints and
// `facet docs --cost` reads back, checked, with every problem named by its key path.
#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "analysis/cost.h"
#include "catalog/catalog.h"
#include "catalog/checker.h"
#include "core/diagnostics.h"
#include "core/io.h"
#include "renderers/renderer.h"

namespace facet {

using nlohmann::json;

double CostCell::number(const std::string& key) const {
  auto it = figures.find(key);
  return it != figures.end() && it->is_number() ? it->get<double>() : 0;
}

bool CostCell::flag(const std::string& key) const {
  auto it = figures.find(key);
  return it != figures.end() && it->is_boolean() && it->get<bool>();
}

const CostCell& CostRow::cell(const std::string& target) const {
  static const CostCell none;
  auto it = cells.find(target);
  return it == cells.end() ? none : it->second;
}

bool CostRow::ok() const {
  return std::all_of(cells.begin(), cells.end(), [](const auto& c) { return c.second.error.empty(); });
}

const CostRow* CostTable::find(const std::string& name) const {
  for (const auto& r : rows)
    if (r.name == name) return &r;
  return nullptr;
}

const std::vector<CostTargetFormat>& cost_format() {
  // The figures each target's cell has, by its renderer's name.
  static const std::map<std::string, CostTargetFormat> by_target = {
      {"glsl",
       {"glsl",
        {{"spirv", "SPIR-V instructions", CostFigureKind::Count},
         {"callgrind_per_pixel", "instructions / pixel (callgrind)", CostFigureKind::Number},
         {"callgrind_relative", "relative to the baseline", CostFigureKind::Ratio}},
        "callgrind_per_pixel",
        "callgrind_relative"}},
      {"osl",
       {"osl",
        {{"instructions", "OSL instructions", CostFigureKind::Count},
         {"ns_per_pixel", "ns / pixel", CostFigureKind::Number},
         {"relative", "relative to the baseline", CostFigureKind::Ratio}},
        "ns_per_pixel",
        "relative"}},
      {"pov",
       {"pov",
        {{"native", "POV-Ray's own finish", CostFigureKind::Flag},
         {"functions", "function pigments", CostFigureKind::CountOrNull},
         {"ns_per_pixel", "ns / pixel", CostFigureKind::Number},
         {"relative", "relative to the baseline", CostFigureKind::Ratio}},
        "ns_per_pixel",
        "relative"}},
  };
  static const std::vector<CostTargetFormat> formats = [] {
    std::vector<CostTargetFormat> out;
    for (const auto& e : renderer_registry())
      if (auto it = by_target.find(e.info.name); it != by_target.end()) out.push_back(it->second);
    return out;
  }();
  return formats;
}

// ---------------------------------------------------------------- writing

namespace {

json or_null(double x) { return x > 0 ? json(x) : json(nullptr); }

json row_json(const CostRow& r) {
  json row = {{"name", r.name},
              {"material", r.material},
              {"diffuse", r.diffuse.empty() ? json(nullptr) : json(r.diffuse)},
              {"specular", r.specular.empty() ? json(nullptr) : json(r.specular)}};
  if (!r.layers.empty()) row["layers"] = r.layers;
  for (const auto& format : cost_format()) {
    const CostCell& c = r.cell(format.target);
    row[format.target] = c.error.empty() ? c.figures : json{{"error", c.error}};
  }
  return row;
}

json frame_json(const CostBaselines& b) {
  return {{"glsl_spirv", b.spirv_empty},
          {"hlsl_spirv", b.hlsl_spirv_empty},
          {"glsl_callgrind_per_pixel", or_null(b.callgrind_empty_per_pixel)},
          {"osl_emission_ns_per_pixel", or_null(b.cycles_emission_ns_per_pixel)}};
}

json tools_json(const CostBaselines& b) {
  return {{"gl_renderer", b.gl_renderer}, {"blender", b.blender}, {"osl", b.osl},
          {"povray", b.povray},           {"glslang", b.glslang}, {"spirv_tools", b.spirv_tools},
          {"valgrind", b.valgrind}};
}

}  // namespace

json costs_json(const std::vector<CostRow>& rows, const CostBaselines& b) {
  json out = {{"baseline", cost_baseline_model().name}, {"rows", json::array()}};
  for (const auto& r : rows) out["rows"].push_back(row_json(r));
  out["frame"] = frame_json(b);
  out["tools"] = tools_json(b);
  return out;
}

CostTable cost_table(const std::vector<CostRow>& rows, const CostBaselines& b, const std::string& source) {
  CostTable t;
  t.source = source;
  t.baseline = cost_baseline_model().name;
  // The rows as `facet cost --json` prints them: an error drops the cell's figures.
  for (const auto& r : rows) {
    CostRow row = r;
    for (auto& [target, c] : row.cells)
      if (!c.error.empty()) c.figures = json::object();
    t.rows.push_back(std::move(row));
  }
  t.frame = frame_json(b);
  t.tools = tools_json(b);
  return t;
}

// ---------------------------------------------------------------- reading

namespace {

// One target's object: {"error": why} or its figures.
CostCell parse_cell(const json& j, const CostTargetFormat& format, const std::string& path, DiagnosticSink& sink) {
  CostCell cell;
  if (!j.is_object()) {
    sink.error(path, fmt::format("expected an object (the figures, or {{\"error\": \"why\"}}), found {}", json_type_name(j)));
    return cell;
  }
  if (j.contains("error")) {
    if (!j["error"].is_string() || j["error"].get<std::string>().empty())
      sink.error(join_path(path, "error"), "expected a non-empty string: why the target was not measured");
    else cell.error = j["error"].get<std::string>();
    return cell;
  }
  Checker check(sink);
  for (const CostFigureDef& d : format.figures) {
    std::string p = join_path(path, d.key);
    if (!j.contains(d.key)) {
      sink.error(p, "missing; the cost format names it");
      continue;
    }
    const json& v = j[d.key];
    bool ok = true;
    if (d.kind == CostFigureKind::Flag) {
      ok = v.is_boolean();
      if (!ok) sink.error(p, fmt::format("expected a boolean, found {}", json_type_name(v)));
    } else if (!(d.kind != CostFigureKind::Count && v.is_null())) {  // null: not measured (e.g. facet cost --no-timings)
      bool count = d.kind == CostFigureKind::Count || d.kind == CostFigureKind::CountOrNull;
      const char* allowed = d.kind == CostFigureKind::CountOrNull ? "null or a whole number ≥ 0"
                            : count                                 ? "a whole number ≥ 0"
                                                                    : "a number ≥ 0, or null (not measured)";
      auto x = check.number(v, p, allowed);
      ok = x && *x >= 0 && (!count || v.is_number_integer());
      if (x && !ok) sink.error(p, fmt::format("{} is not allowed; allowed: {}", v.dump(), allowed));
    }
    if (ok) cell.figures[d.key] = v;
  }
  // Figures a newer cost command adds are kept as they are.
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    const json& v = item.value();
    const auto& defs = format.figures;
    if (std::any_of(defs.begin(), defs.end(), [&](const CostFigureDef& d) { return key == d.key; })) continue;
    if (v.is_number() || v.is_boolean() || v.is_string() || v.is_null()) cell.figures[key] = v;
    else sink.error(join_path(path, key), fmt::format("expected a number, boolean, string or null, found {}", json_type_name(v)));
  }
  return cell;
}

std::string string_or_null(const json& row, const char* key, const std::string& path, DiagnosticSink& sink,
                           bool nullable) {
  if (!row.contains(key)) {
    sink.error(join_path(path, key), nullable ? "missing; allowed: a model name or null" : "missing; allowed: a string");
    return "";
  }
  const json& v = row[key];
  if (nullable && v.is_null()) return "";
  if (!v.is_string() || v.get<std::string>().empty()) {
    sink.error(join_path(path, key), fmt::format("expected a non-empty string{}, found {}", nullable ? " or null" : "",
                                                 json_type_name(v)));
    return "";
  }
  return v.get<std::string>();
}

CostRow parse_row(const json& row, const std::string& path, DiagnosticSink& sink) {
  std::vector<std::string> keys = {"name", "material", "diffuse", "specular", "layers"};
  for (const auto& format : cost_format()) keys.push_back(format.target);
  CostRow r;
  if (!row.is_object()) {
    sink.error(path, fmt::format("expected an object (one row), found {}", json_type_name(row)));
    return r;
  }
  for (const auto& [key, v] : row.items())
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      std::string hint = suggest(key, keys);
      sink.error(join_path(path, key), fmt::format("unknown key{}; allowed keys: {}",
                                                   hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted_list(keys)));
    }
  r.name = string_or_null(row, "name", path, sink, false);
  r.material = string_or_null(row, "material", path, sink, false);
  r.diffuse = string_or_null(row, "diffuse", path, sink, true);
  r.specular = string_or_null(row, "specular", path, sink, true);
  if (row.contains("layers")) {  // optional: a row of a material without layers has none
    const json& layers = row["layers"];
    for (size_t i = 0; layers.is_array() && i < layers.size(); ++i)
      if (layers[i].is_string() && !layers[i].get<std::string>().empty()) r.layers.push_back(layers[i].get<std::string>());
      else sink.error(join_path(path, fmt::format("layers[{}]", i)), "expected a layer model's name");
    if (!layers.is_array())
      sink.error(join_path(path, "layers"), fmt::format("expected a list of layer model names, found {}", json_type_name(layers)));
  }
  for (const auto& format : cost_format()) {
    const std::string& t = format.target;
    if (!row.contains(t)) {
      sink.error(join_path(path, t), "missing; allowed: the target's figures or {\"error\": \"why\"}");
      continue;
    }
    r.cell(t) = parse_cell(row[t], format, join_path(path, t), sink);
  }
  return r;
}

void parse_rows(const json& doc, CostTable& table, DiagnosticSink& sink) {
  if (!doc.contains("rows")) {
    sink.error("rows", "missing; allowed: an array of rows");
    return;
  }
  if (!doc["rows"].is_array()) {
    sink.error("rows", fmt::format("expected an array of rows, found {}", json_type_name(doc["rows"])));
    return;
  }
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < doc["rows"].size(); ++i) {
    std::string path = index_path("rows", i);
    CostRow r = parse_row(doc["rows"][i], path, sink);
    if (!r.name.empty() && !seen.emplace(r.name, i).second)
      sink.error(join_path(path, "name"), fmt::format("\"{}\" is also rows[{}]; allowed: one row per name", r.name, seen[r.name]));
    table.rows.push_back(std::move(r));
  }
}

}  // namespace

CostTable parse_cost_rows(const json& doc, const std::string& file) {
  DiagnosticSink sink(file);
  CostTable table;
  table.source = file;
  if (!doc.is_object()) {
    sink.error("", fmt::format("expected an object {{\"baseline\", \"rows\"}} (facet cost --json), found {}", json_type_name(doc)));
    sink.throw_if_any();
  }
  static const std::vector<std::string> keys = {"baseline", "rows", "frame", "tools"};
  for (const auto& [key, v] : doc.items())
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      sink.error(key, "unknown key; allowed keys: " + quoted_list(keys));
  // The frame's cost and the tools' versions: shown as they are.
  for (auto [key, object] : {std::pair{"frame", &table.frame}, std::pair{"tools", &table.tools}}) {
    if (!doc.contains(key)) continue;
    if (!doc[key].is_object()) sink.error(key, fmt::format("expected an object, found {}", json_type_name(doc[key])));
    else *object = doc[key];
  }
  table.baseline = string_or_null(doc, "baseline", "", sink, false);
  parse_rows(doc, table, sink);
  sink.throw_if_any();
  return table;
}

CostTable load_cost_rows(const std::string& path) { return parse_cost_rows(read_json_file(path), path); }

}  // namespace facet
