// facet — running the external tools (povray, Blender's Python) and capturing what they say.
#pragma once

#include <string>
#include <vector>

namespace facet {

struct ProcessResult {
  int exit_code = -1;   // -1: could not start; 128 + n: killed by signal n
  std::string output;   // stdout and stderr together
  double seconds = 0;
};

// The files a child may touch, enforced by the kernel (Landlock, Linux 5.13 and later) from
// before the program starts: POV-Ray 3.7's own I/O restrictions are never in force (its
// povray.conf parser compares each setting with `!=`, so every file I/O setting reads as
// unset; measured on Debian's 3.7.0.10: `#fopen` writes /var/tmp whatever povray.conf says).
struct FileAccess {
  std::vector<std::string> read;        // folders (with everything under them) and files, read and run
  std::vector<std::string> read_write;  // folders the program may also create, write and remove files in
};
// The Landlock ABI version this kernel offers; 0 when it has none (FileAccess is then not enforced).
int landlock_abi();

// Runs argv[0] (searched on PATH) in `cwd` with extra environment entries "K=V"; with
// `access`, confined to it (where the kernel has Landlock).
ProcessResult run_process(const std::vector<std::string>& argv, const std::string& cwd = "",
                          const std::vector<std::string>& env = {}, const FileAccess* access = nullptr);
// POV-Ray with `args` (after "povray") in the folder `dir`, confined (where the kernel has
// Landlock) to reading the system's programs and libraries and POV-Ray's own files, and to
// reading and writing `dir`: the scene, the images facet decoded for it, its output. A
// generated scene's `#fopen`, `#include` or `#read` of any other file fails.
ProcessResult run_povray(const std::vector<std::string>& args, const std::string& dir);
// The full path of a program on PATH, or "".
std::string find_program(const std::string& name);

}  // namespace facet
