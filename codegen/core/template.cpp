#include "core/template.h"

#include <set>
#include <stdexcept>

namespace facet {

std::string fill_embedded(const std::map<std::string, std::string>& files, const std::string& path,
                          const std::map<std::string, std::string>& values) {
  auto it = files.find(path);
  if (it == files.end()) throw std::logic_error("facet: no template " + path);
  return fill_template(path, it->second, values);
}

std::string fill_template(const std::string& path, const std::string& t,
                          const std::map<std::string, std::string>& values) {
  size_t size = t.size();
  for (const auto& [k, v] : values) size += v.size();
  std::string out;
  out.reserve(size);  // generate() fills a few templates with a few kB each
  std::set<std::string> used;
  size_t pos = 0;
  while (true) {
    size_t open = t.find("{{", pos);
    if (open == std::string::npos) break;
    size_t close = t.find("}}", open);
    if (close == std::string::npos) throw std::logic_error("facet: unclosed {{ in template " + path);
    std::string key = t.substr(open + 2, close - open - 2);
    auto v = values.find(key);
    if (v == values.end()) throw std::logic_error("facet: template " + path + " needs a value for " + key);
    out.append(t, pos, open - pos);
    out += v->second;
    used.insert(std::move(key));
    pos = close + 2;
  }
  out.append(t, pos, std::string::npos);
  if (used.size() != values.size())
    for (const auto& [k, v] : values)
      if (!used.count(k)) throw std::logic_error("facet: template " + path + " has no placeholder " + k);
  return out;
}

}  // namespace facet
