#pragma once

// The names inside a session's folder, and where deleted episodes go: shared by opening and
// committing (session.cc) and editing episodes (session_episodes.cc). Internal to engine/store.

#include <filesystem>
#include <string>

namespace recon::store {

inline constexpr char kManifestName[] = "session.json";
inline constexpr char kIndexName[] = "session.hdf5";
inline constexpr char kDemoFolder[] = "episodes";
inline constexpr char kPlayFolder[] = "play";
inline constexpr char kTrashFolder[] = "trash";
inline constexpr char kLockName[] = ".lock";

/// A free name for episode `name` in the trash folder `trash`: name.h5, else name.1.h5, ...
inline std::string TrashName(const std::filesystem::path& trash, const std::string& name) {
  std::filesystem::path target = trash / (name + ".h5");
  for (int i = 1; std::filesystem::exists(target); ++i) {
    target = trash / (name + "." + std::to_string(i) + ".h5");
  }
  return target.string();
}

}  // namespace recon::store
