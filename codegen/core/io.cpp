#include "core/io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/text.h"

namespace facet {

namespace {

bool process_gone(const std::string& pid_text) {
  if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9)
    return false;
  const pid_t pid = pid_t(std::stol(pid_text));
  return pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH;
}

// Removes the entries of `dir` named <prefix><pid>-<anything><suffix>, owned by this user,
// whose process `pid` is gone: what a killed run left.
void remove_leftovers(const std::filesystem::path& dir, const std::string& prefix, bool folders) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const size_t dash = name.find('-', prefix.size());
    if (dash == std::string::npos || !process_gone(name.substr(prefix.size(), dash - prefix.size()))) continue;
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0 || st.st_uid != ::getuid()) continue;
    if (folders ? S_ISDIR(st.st_mode) : S_ISREG(st.st_mode)) {
      std::error_code rm;
      fs::remove_all(it->path(), rm);
    }
  }
}

// Each folder facet writes into is cleared of killed runs' temporary files once a process.
void clear_leftovers_once(const std::filesystem::path& dir) {
  static std::mutex mutex;
  static std::set<std::string> done;
  std::error_code ec;
  const std::string key = std::filesystem::absolute(dir, ec).lexically_normal().string();
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!done.insert(key).second) return;
  }
  remove_leftovers(dir, ".facet-", false);
}

}  // namespace

const std::string& private_work_folder() {
  struct Folder {
    std::string path;
    Folder() {
      namespace fs = std::filesystem;
      const fs::path tmp = fs::temp_directory_path();
      remove_leftovers(tmp, "facet-", true);
      std::string tmpl = (tmp / ("facet-" + std::to_string(::getpid()) + "-XXXXXX")).string();
      if (!::mkdtemp(tmpl.data()))
        throw IoError(tmp.string() + ": cannot make a private work folder: " + std::strerror(errno));
      path = tmpl;
    }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static Folder folder;
  return folder.path;
}

FolderLock::FolderLock(const std::string& folder, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder))
    throw IoError(option + " " + folder + ": " +
                  (fs::exists(folder) ? std::string("is a file, not a folder")
                                      : "cannot make the folder: " + (ec ? ec.message() : std::string("unknown error"))));
  const std::string file = (fs::path(folder) / ".facet.lock").string();
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError(option + " " + folder + ": cannot write in the folder: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char pid[32] = {};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    ::close(fd_);
    throw IoError(option + " " + folder + ": another facet run" +
                  (n > 0 ? " (process " + std::string(pid, size_t(n)) + ")" : std::string()) +
                  " is writing there; wait for it to finish or choose another folder");
  }
  const std::string me = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) != ssize_t(me.size())) {
    // the lock holds without the number, which only makes the message above plainer
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  clear_leftovers_once(dir);
  // Named with this process's id, so that the next run knows a killed run's file for one.
  std::string tmpl = (dir / (".facet-" + std::to_string(::getpid()) + "-" + target.filename().string().substr(0, 100) +
                             "-XXXXXX")).string();
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

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string size_text(uint64_t bytes) {
  return bytes >= (uint64_t(1) << 30) ? std::to_string(bytes >> 30) + " GiB" : std::to_string(bytes >> 20) + " MiB";
}

}  // namespace

std::string read_file(const std::string& path, uint64_t limit) {
  // O_NONBLOCK: opening a FIFO with no writer returns at once (then fstat refuses it).
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw IoError(path + ": cannot open the file for reading: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw IoError(path + ": cannot read the file: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw IoError(path + ": is " + kind_of(st.st_mode) + ", not a file facet can read");
  if (uint64_t(st.st_size) > limit)
    throw IoError(path + ": is " + std::to_string(st.st_size) + " bytes, more than facet reads from one file (" +
                  size_text(limit) + ")");
  std::string out(size_t(st.st_size), '\0');
  size_t got = 0;
  while (got < out.size()) {
    const ssize_t n = ::read(fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(path + ": cannot read the file: " + std::strerror(errno));
    if (n == 0) break;  // shrank while read
    got += size_t(n);
  }
  out.resize(got);
  return out;
}

namespace {

std::vector<std::filesystem::path>& allowed() {
  static std::vector<std::filesystem::path> folders;
  return folders;
}

// The folder, symbolic links followed, as far as it exists.
std::filesystem::path resolved(const std::filesystem::path& p) {
  std::error_code ec;
  std::filesystem::path r = std::filesystem::weakly_canonical(std::filesystem::absolute(p, ec), ec);
  return ec ? std::filesystem::path() : r;
}

bool inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  if (folder.empty() || file.empty()) return false;
  auto f = file.begin();
  for (auto d = folder.begin(); d != folder.end(); ++d, ++f) {
    if (d->empty() && std::next(d) == folder.end()) break;  // a trailing separator
    if (f == file.end() || *f != *d) return false;
  }
  return true;
}

}  // namespace

void allow_folder(const std::string& dir) {
  const std::filesystem::path r = resolved(dir);
  if (!r.empty()) allowed().push_back(r);
}

std::string confined_path(const std::string& folder, const std::string& reference) {
  namespace fs = std::filesystem;
  if (reference.empty() || reference.find('\0') != std::string::npos) return "";
  const fs::path base = folder.empty() ? fs::path(".") : fs::path(folder);
  const fs::path ref(reference);
  const fs::path file = resolved(ref.is_absolute() ? ref : base / ref);
  if (file.empty()) return "";
  if (inside(file, resolved(base))) return file.string();
  for (const auto& a : allowed())
    if (inside(file, a)) return file.string();
  return "";
}

bool inside_folder(const std::string& file, const std::string& folder) {
  return inside(resolved(file), resolved(folder.empty() ? std::string(".") : folder));
}

std::string allowed_folders_text() {
  std::string out;
  for (const auto& a : allowed()) out += (out.empty() ? "" : ", ") + a.string();
  return out;
}

std::string outside_folder_message(const std::string& reference, const std::string& folder, const std::string& namer,
                                   const std::string& own) {
  const std::string allowed = allowed_folders_text();
  const std::filesystem::path base = folder.empty() ? std::filesystem::path(".") : std::filesystem::path(folder);
  return "\"" + one_line(reference) + "\" cannot be used: facet reads the files " + namer + " names only inside " + own +
         " own folder (" + std::filesystem::absolute(base).lexically_normal().string() + ")" +
         (allowed.empty() ? "" : " and the allowed " + allowed) + "; --allow-path DIR allows another folder";
}

}  // namespace facet
