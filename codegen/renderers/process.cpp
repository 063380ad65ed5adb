#include "renderers/process.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <string_view>

#include <dlfcn.h>
#include <fcntl.h>
#include <linux/landlock.h>
#include <link.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "renderers/backends.h"

extern char** environ;

namespace facet {

std::string find_program(const std::string& name) {
  if (name.find('/') != std::string::npos) return access(name.c_str(), X_OK) == 0 ? name : "";
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    std::string p = (dir.empty() ? "." : dir) + "/" + name;
    if (access(p.c_str(), X_OK) == 0) return p;
  }
  return "";
}

namespace {

// The process groups of the children running now: a signal that ends facet (Ctrl-C,
// SIGTERM, SIGHUP) ends them too. Each child leads a group of its own, so that whatever it
// starts (Chromium's helpers) goes with it, and asks the kernel to kill it when facet dies
// however facet dies (PR_SET_PDEATHSIG: `kill -9` leaves no POV-Ray running).
constexpr size_t kMaxChildren = 256;
std::atomic<pid_t> running[kMaxChildren];

void end_children_and_die(int sig) {
  for (auto& slot : running) {
    const pid_t pid = slot.load();
    if (pid > 0) ::kill(-pid, SIGKILL);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void forward_fatal_signals() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // nohup: stay ignored
      struct sigaction sa {};
      sa.sa_handler = end_children_and_die;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

struct Running {
  std::atomic<pid_t>* slot = nullptr;
  explicit Running(pid_t pid) {
    for (auto& s : running) {
      pid_t empty = 0;
      if (s.compare_exchange_strong(empty, pid)) {
        slot = &s;
        return;
      }
    }
  }
  ~Running() {
    if (slot) slot->store(0);
  }
};

// Landlock (Documentation/userspace-api/landlock.rst): the rights a ruleset handles, by ABI.
constexpr uint64_t kFileRights = LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_WRITE_FILE |
                                 LANDLOCK_ACCESS_FS_READ_FILE | (1ULL << 14) /* TRUNCATE, ABI 3 */;
constexpr uint64_t kReadRights = LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR;

uint64_t handled_rights(int abi) {
  uint64_t all = (1ULL << 13) - 1;  // ABI 1: EXECUTE … MAKE_SYM
  if (abi >= 2) all |= 1ULL << 13;  // REFER
  if (abi >= 3) all |= 1ULL << 14;  // TRUNCATE
  return all;
}

// In the child, between fork and exec (system calls only): the kernel confines this
// process and what it runs to `read` and `read_write`. False when it could not.
bool confine(const std::vector<const char*>& read, const std::vector<const char*>& read_write, int abi) {
  const uint64_t all = handled_rights(abi);
  landlock_ruleset_attr attr{};
  attr.handled_access_fs = all;
  const int rules = int(syscall(SYS_landlock_create_ruleset, &attr, sizeof attr, 0));
  if (rules < 0) return false;
  auto allow = [&](const char* path, uint64_t rights) {
    const int fd = open(path, O_PATH | O_CLOEXEC);
    if (fd < 0) return;  // not on this system
    struct stat st {};
    if (fstat(fd, &st) == 0 && !S_ISDIR(st.st_mode)) rights &= kFileRights;
    landlock_path_beneath_attr beneath{};
    beneath.allowed_access = rights & all;
    beneath.parent_fd = fd;
    syscall(SYS_landlock_add_rule, rules, LANDLOCK_RULE_PATH_BENEATH, &beneath, 0);
    close(fd);
  };
  for (const char* p : read) allow(p, kReadRights);
  for (const char* p : read_write) allow(p, all);
  const bool ok = prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0 && syscall(SYS_landlock_restrict_self, rules, 0) == 0;
  close(rules);
  return ok;
}

}  // namespace

int landlock_abi() {
  static const int abi = [] {
    const long v = syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
    return v > 0 ? int(v) : 0;
  }();
  return abi;
}

ProcessResult run_process(const std::vector<std::string>& argv, const std::string& cwd,
                          const std::vector<std::string>& env, const FileAccess* access) {
  ProcessResult r;
  std::string exe = find_program(argv.at(0));
  if (exe.empty()) {
    r.output = argv[0] + ": not found on PATH";
    return r;
  }
  int pipefd[2];
  if (pipe(pipefd) != 0) {
    r.output = std::string("pipe: ") + std::strerror(errno);
    return r;
  }
  forward_fatal_signals();
  // Everything the child needs is made before fork(): between fork and exec the child of this
  // multithreaded process may only make system calls. Another thread may hold the allocator's
  // lock at the fork, and a child that allocates then waits for it forever (seen under ASan: a
  // POV-Ray run's child spinning in the sanitizer's allocator, the suite stopped). So the
  // argument vector and the environment (environ with `env`'s NAME=value in place of the same
  // names, as putenv would set them) are built here, and the child calls execve with them.
  std::vector<const char*> may_read, may_write;
  if (access) {
    for (const auto& p : access->read) may_read.push_back(p.c_str());
    for (const auto& p : access->read_write) may_write.push_back(p.c_str());
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  auto name_of = [](const char* e) {
    const char* eq = std::strchr(e, '=');
    return std::string_view(e, eq ? size_t(eq - e) : std::strlen(e));
  };
  std::vector<char*> envp;
  for (char** e = environ; *e; ++e)
    if (std::none_of(env.begin(), env.end(), [&](const std::string& x) { return name_of(x.c_str()) == name_of(*e); }))
      envp.push_back(*e);
  for (const auto& x : env) envp.push_back(const_cast<char*>(x.c_str()));
  envp.push_back(nullptr);
  const int abi = access ? landlock_abi() : 0;
  auto start = std::chrono::steady_clock::now();
  const pid_t parent = getpid();
  pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);  // facet died before the line above
    dup2(pipefd[1], 1);
    dup2(pipefd[1], 2);
    close(pipefd[0]);
    close(pipefd[1]);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(127);
    if (abi > 0 && !confine(may_read, may_write, abi)) {
      static const char kWhy[] = "facet: cannot confine the program to its files (Landlock)\n";
      (void)!write(2, kWhy, sizeof kWhy - 1);
      _exit(126);
    }
    execve(exe.c_str(), args.data(), envp.data());
    _exit(127);
  }
  close(pipefd[1]);
  if (pid < 0) {
    close(pipefd[0]);
    r.output = std::string("fork: ") + std::strerror(errno);
    return r;
  }
  setpgid(pid, pid);  // as the child does: whichever runs first, the group exists before a signal
  const Running tracked(pid);
  char buf[65536];
  ssize_t n;
  while ((n = read(pipefd[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0) r.output.append(buf, size_t(n));
  close(pipefd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  ::kill(-pid, SIGKILL);  // what the child started and left behind (its group); nothing when none
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

ProcessResult run_povray(const std::vector<std::string>& args, const std::string& dir) {
  std::vector<std::string> argv = {"povray"};
  argv.insert(argv.end(), args.begin(), args.end());
  FileAccess access;
  // Measured: what POV-Ray 3.7 opens to start (its program and libraries, the loader's
  // cache, /etc/povray's povray.conf and povray.ini, its include folder under /usr/share)
  // and to count the processors.
  access.read = {"/usr", "/lib", "/lib64", "/bin", "/etc/povray", "/etc/ld.so.cache", "/dev/null",
                 "/dev/urandom", "/sys/devices/system/cpu", "/proc/self", "/proc/cpuinfo", "/proc/meminfo"};
  const std::string program = find_program("povray");  // a povray outside /usr (a user's own build)
  if (!program.empty()) access.read.push_back(std::filesystem::path(program).parent_path().string());
  access.read_write = {std::filesystem::absolute(dir).string()};
  return run_process(argv, dir, {}, &access);
}

// LeakSanitizer looks for leaks at exit, after EGL (or the Vulkan loader) has unloaded Mesa's driver:
// memory that only the driver's globals still point to then looks leaked (from
// "<unknown module>"), since an unloaded library's data is no longer scanned.
// In leak-checked builds every library loaded once the context exists is
// pinned (never unloaded), so such memory stays reachable and what LeakSanitizer
// reports is facet's own.
void pin_loaded_libraries() {
#ifdef FACET_LEAK_CHECKED
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void*) {
        if (info->dlpi_name && *info->dlpi_name) dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
#endif
}

}  // namespace facet
