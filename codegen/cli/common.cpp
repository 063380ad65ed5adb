// The command line's shared helpers.
#include "cli/command.h"

#include "core/diagnostics.h"
#include "renderers/renderer.h"

#include <fmt/format.h>

#include <sstream>
#include <string>
#include <vector>

namespace facet::cli {

// The material argument may be left out for a POV-Ray scene whose objects all carry their own materials.
std::optional<Material> load_optional_material(const std::string& path, const std::optional<Scene>& scene,
                                               const std::string& why) {
  if (!path.empty()) return load_material(path);
  if (scene && scene->has_own_materials()) return std::nullopt;
  throw InputError({{"command line", "MATERIAL", "a material file is required " + why, 0, 0}});
}

bool parse_size(const std::string& s, int& w, int& h) {
  auto x = s.find('x');
  if (x == std::string::npos) return false;
  try {
    w = std::stoi(s.substr(0, x));
    h = std::stoi(s.substr(x + 1));
  } catch (...) {
    return false;
  }
  return w > 0 && h > 0 && w <= 16384 && h <= 16384;
}

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string renderer_choices() {
  std::string out;
  for (const auto& name : renderer_names()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

std::string all_renderers() {
  std::string out;
  for (const auto& name : renderer_names()) out += (out.empty() ? "" : ",") + name;
  return out;
}

std::string renderer_help() {
  std::string out;
  for (const auto& e : renderer_registry()) out += fmt::format("  {:<10} {}\n", e.info.name, e.info.summary);
  return out;
}

std::vector<std::string> renderer_list(const std::string& option, const std::string& names) {
  std::vector<std::string> out;
  for (const auto& r : split_commas(names)) {
    if (!find_renderer(r))
      throw InputError({{"command line", option, "unknown renderer \"" + r + "\"; allowed: " + renderer_choices(), 0, 0}});
    out.push_back(r);
  }
  return out;
}

}  // namespace facet::cli
