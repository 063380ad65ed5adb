// Helpers the tests that run the facet binary share: a scratch folder per
// process and test suite, and `facet ARGS…` run as a user runs it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/io.h"
#include "renderers/process.h"

namespace facet::test {

// A file (or folder) name in a folder of this process for one test suite, e.g. scratch("cli", "a.frag"):
// under private_work_folder(), made new by mkdtemp and removed when the process ends, so a folder
// an earlier process with the same pid left (pids are reused; /tmp outlives a CI run) cannot show
// its files to a test that checks something was not written.
inline std::filesystem::path scratch(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(private_work_folder()) / ("test-" + suite);
  std::filesystem::create_directories(dir);
  return dir / name;
}

// RFC 4648 base64 of `bytes`, for data URIs the tests write.
inline std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
    out += k[(n >> 18) & 63];
    out += k[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[n & 63] : '=';
  }
  return out;
}

// The bytes of a base64 data URI (what base64() encodes, after the comma).
inline std::string base64_decode(const std::string& uri) {
  static const std::string k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t acc = 0;
  int bits = 0;
  for (char ch : uri.substr(uri.find(',') + 1)) {
    const size_t v = k.find(ch);
    if (v == std::string::npos) continue;  // '=' padding
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(char((acc >> bits) & 0xff));
    }
  }
  return out;
}

#ifdef FACET_BIN
// The facet binary with `args`, standard input from `stdin_file` when given; output is stdout and stderr together.
inline ProcessResult facet(const std::vector<std::string>& args, const std::string& stdin_file = "") {
  std::string cmd = "'" + std::string(FACET_BIN) + "'";
  for (const auto& a : args) cmd += " '" + a + "'";
  if (!stdin_file.empty()) cmd += " < '" + stdin_file + "'";
  return run_process({"sh", "-c", cmd});
}
#endif

}  // namespace facet::test
