#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace recon {

/// Writes `content` to `path` atomically: to a temporary file in the same folder, flushed, then
/// renamed over `path`. A crash or error leaves any previous file intact. Throws UserError naming
/// the path if it cannot be written.
void WriteFileAtomically(const std::string& path, const std::string& content);

/// Writes `content` to `path` in place (created or truncated), without a rename: for files
/// that are themselves temporaries. On failure the part written is removed and a UserError says
/// "cannot write <path>: <the system's reason>".
void WriteWholeFile(const std::string& path, const std::string& content);

/// Which file is at a path and when it was last written: a file replaced whole (renamed over, as
/// WriteFileAtomically does) has a new inode, so a change shows whatever the file system's time
/// resolution.
struct FileStamp {
  uint64_t inode = 0;
  int64_t modified_ns = 0;
  bool operator==(const FileStamp& other) const = default;
};
/// The stamp of the file at `path`; nullopt when there is none.
std::optional<FileStamp> StampOf(const std::string& path);

/// Files read whole (JSON, scripts, plans, logs) are at most this big: a session's largest is a
/// few megabytes, and parsing a bigger one would take many times its size in memory.
inline constexpr int64_t kMaxWholeFileBytes = int64_t{256} << 20;

/// Refuses a path that exists but is not a regular file (symbolic links are followed): a folder,
/// a named pipe, a device or a socket. Opening a named pipe waits for a writer that never comes
/// and a device such as /dev/zero never ends, so every reader of a file asks first. Throws
/// UserError "<path>: is a named pipe (FIFO), not a file"; a missing path is left to the caller,
/// which says what the file was for.
void RefuseNonRegularFile(const std::string& path);

/// The whole content of the file at `path`, byte for byte; nullopt when it cannot be opened
/// (missing or unreadable), so that each caller names what the file was for. A path that is not a
/// regular file (see RefuseNonRegularFile) or a file over `max_bytes` is a UserError naming it.
std::optional<std::string> ReadWholeFile(const std::string& path,
                                         int64_t max_bytes = kMaxWholeFileBytes);

/// Creates `dir` (and parents) if needed and checks that a file can be created in it. Throws
/// UserError naming the folder otherwise. Call before long work so it fails fast.
void EnsureWritableDirectory(const std::string& dir);

/// A path of a temporary file next to `path` (same folder, so rename is atomic):
/// "<path>.tmp.<pid of the writer>".
std::string TemporarySibling(const std::string& path);

/// `message` with every mention of the temporary `tmp` replaced by the file it stands for, so a
/// failed write names what the user asked for ("cannot write demo_3.h5: No space left on device").
std::string NameTheTarget(std::string message, const std::string& tmp, const std::string& target);

/// True when `file_name` is a TemporarySibling whose writer process no longer runs (it was
/// killed before its rename): such a file is garbage and may be removed. `marker` is what
/// precedes the writer's pid: ".tmp." for files, ".importing." for an import's staging folder.
bool IsTemporaryOfDeadWriter(const std::string& file_name, const std::string& marker = ".tmp.");

/// Removes every "<path>.importing.<pid>" folder (a staging folder, see ImportRobomimic) whose
/// writer is dead, with its contents; returns how many.
int RemoveDeadStagingFoldersOf(const std::string& path, const std::string& marker);
/// Removes the temporaries of dead writers in `folder` whose names start with `prefix` (all of
/// them for ""); returns how many. Errors are ignored (the next writer tries again).
int RemoveDeadTemporariesIn(const std::string& folder, const std::string& prefix = "");
/// Removes the temporaries that dead writers of `path` left beside it; returns how many.
int RemoveDeadTemporariesOf(const std::string& path);

/// Renames `from` over `to` (atomic on one file system). Throws UserError on failure.
void ReplaceFile(const std::string& from, const std::string& to);

/// Flushes a file's contents to the disk (fsync), so that a rename made after it survives a power
/// loss with the contents in place. Throws UserError naming the path.
void SyncFile(const std::string& path);
/// Flushes a folder's entries (a rename into it) to the disk. Errors are ignored: some file
/// systems do not support it, and the rename itself has already happened.
void SyncDirectory(const std::string& dir);

}  // namespace recon
