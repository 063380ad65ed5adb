// facet — files written whole or not at all, files read within stated limits, and the
// folders a file may name other files in.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace facet {

class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `content` to a temporary file beside `path`, then renames it over
// `path`: readers see the old file or the new one, never a part. On failure
// the temporary file is removed, `path` is untouched, and IoError names it.
void write_file_atomic(const std::string& path, const std::string& content);
// The same for a file too big to hold: `write` streams it into the temporary file.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write);

// The most bytes facet reads from one file (README, "Reliability"): glTF addresses a buffer
// with 32 bits, so no file facet needs is bigger. A material or scene document (JSON, inline
// meshes included) is read up to kMaxDocumentBytes.
inline constexpr uint64_t kMaxFileBytes = uint64_t(4) << 30;      // 4 GiB
inline constexpr uint64_t kMaxDocumentBytes = uint64_t(1) << 30;  // 1 GiB
// The whole of the regular file `path`, at most `limit` bytes. IoError, naming the path, when
// it cannot be opened, is not a regular file (a folder, a device such as /dev/zero, a FIFO,
// a socket: refused before a byte is read, so nothing blocks or reads without end), or is
// bigger than `limit`.
std::string read_file(const std::string& path, uint64_t limit = kMaxFileBytes);

// This process's private folder for work files: $TMPDIR/facet-<pid>-XXXXXX, made by
// mkdtemp on first use (a fresh name, mode 0700: no other run shares it, no one can plant a
// link in it), removed with everything in it when the process exits normally. Making it
// first removes the folders earlier runs of this user left when they were killed (their
// process is gone), so a `kill -9` leaves nothing past the next run.
const std::string& private_work_folder();

// An output folder held by this run: made if need be (IoError naming it when it cannot be,
// or is a file), then locked (flock on FOLDER/.facet.lock, which the system releases when
// the process ends, however it ends): a second run on the same folder is refused with
// IoError instead of writing over the first's files.
class FolderLock {
 public:
  FolderLock(const std::string& folder, const std::string& option);  // option: "--out", for the message
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

// Files named inside other files — a glTF's buffer and image URIs, a material's or scene's
// texture paths — are read only from
// inside the naming file's folder, after every symbolic link is followed, or from inside a
// folder the user allowed (`--allow-path DIR`). A file from the web cannot make facet read
// /etc/passwd or ~/.ssh, nor learn whether such a file exists.
void allow_folder(const std::string& dir);   // for the rest of the process
// The file `reference` (relative to `folder`, or absolute) names, as an absolute path, when it
// lies inside `folder` or an allowed folder; "" when it lies elsewhere. Whether the file
// exists plays no part: the answer is the same for a file that is there and one that is not.
std::string confined_path(const std::string& folder, const std::string& reference);
// Whether `file` lies inside `folder`, both with symbolic links followed (no allowed folder counts).
bool inside_folder(const std::string& file, const std::string& folder);
// The folders confined_path() accepts besides the naming file's, for messages.
std::string allowed_folders_text();
// The one message for a reference confined_path() refused, the same whether the file exists
// or not: `namer` is what names files ("a glTF"), `own` whose folder ("the glTF's").
std::string outside_folder_message(const std::string& reference, const std::string& folder, const std::string& namer,
                                   const std::string& own);

}  // namespace facet
