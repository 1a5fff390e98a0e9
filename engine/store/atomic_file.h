#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::store {

/// Whether a file written by WriteFileVia must reach the disk before it replaces the old one.
enum class Durability {
  kRename,  ///< atomic against a killed process (the page cache keeps what was written)
  kFsync,   ///< also against a power loss: flushed before the rename, folder flushed after
};

/// Writes `path` through `write(temporary_path)`, then renames the temporary file over `path`.
/// Readers see the old file or the new one, never a part; if `write` throws (or the process
/// dies) the temporary file is removed (or left, for the next write of `path` or Session::Open
/// to remove) and `path` is untouched.
///
/// Temporaries that killed writers of `path` left are removed first, which lists the folder;
/// `sweep` = false skips that where the folder is large and swept otherwise (a session's episode
/// folders, which Session::Open sweeps).
template <typename Write>
void WriteFileVia(const std::string& path, Durability durability, const Write& write,
                  bool sweep = true) {
  if (sweep) RemoveDeadTemporariesOf(path);
  const std::string tmp = TemporarySibling(path);
  try {
    write(tmp);
    if (durability == Durability::kFsync) SyncFile(tmp);
    ReplaceFile(tmp, path);
  } catch (const UserError& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    // The user knows the file they asked for, not our temporary beside it.
    throw UserError(NameTheTarget(e.what(), tmp, path));
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  if (durability == Durability::kFsync) {
    SyncDirectory(std::filesystem::path(path).parent_path().string());
  }
}

}  // namespace recon::store
