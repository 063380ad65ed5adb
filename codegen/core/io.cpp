#include "core/io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace facet {

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmpl = (dir / ("." + target.filename().string() + ".facet-XXXXXX")).string();
  int fd = mkstemp(tmpl.data());
  if (fd < 0) throw IoError(path + ": cannot create a file in " + dir.string() + ": " + std::strerror(errno));
  ::close(fd);
  try {
    {
      std::ofstream out(tmpl, std::ios::binary | std::ios::trunc);
      errno = 0;
      write(out);
      out.flush();
      if (!out) {
        const int err = errno;  // what the failed write(2) set, when it did
        throw IoError(path + ": cannot write" + (err ? std::string(": ") + std::strerror(err) : std::string()));
      }
    }
    int sync = ::open(tmpl.c_str(), O_RDONLY);
    if (sync < 0 || ::fsync(sync) != 0) {
      if (sync >= 0) ::close(sync);
      throw IoError(path + ": cannot flush: " + std::strerror(errno));
    }
    ::close(sync);
    // mkstemp creates 0600; give the file the usual permissions.
    mode_t mask = ::umask(0);
    ::umask(mask);
    ::chmod(tmpl.c_str(), 0666 & ~mask);
    if (std::rename(tmpl.c_str(), path.c_str()) != 0)
      throw IoError(path + ": cannot replace the file: " + std::strerror(errno));
  } catch (...) {
    std::remove(tmpl.c_str());
    throw;
  }
}

void write_file_atomic(const std::string& path, const std::string& content) {
  write_file_atomic(path, [&](std::ostream& out) { out.write(content.data(), std::streamsize(content.size())); });
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace facet
