// Committing a take to a session: the episode file written whole (atomically) or not at all,
// a re-recorded episode's old file kept in the trash, and the index brought up to date.

#include <filesystem>
#include <string>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/store/atomic_file.h"
#include "engine/store/episode_file.h"
#include "engine/store/session.h"
#include "engine/store/session_layout.h"

namespace recon::store {

namespace fs = std::filesystem;

const EpisodeEntry& Session::CommitDemo(const DemoRecord& record,
                                        const std::optional<std::string>& replace) {
  RequireWritable();
  int number = NextDemoNumber();
  if (replace) number = Find(*replace).number;
  if (replace && Find(*replace).name.rfind("demo_", 0) != 0) {
    throw UserError(*replace + " is not a demonstration");
  }
  const std::string name = "demo_" + std::to_string(number);
  const std::string final_path = Path(std::string(kDemoFolder) + "/" + name + ".h5");
  DemoRecord stamped = record;
  stamped.meta.kind = "demo";
  stamped.meta.num_samples = static_cast<int64_t>(record.episode.samples.size());
  if (stamped.meta.recorded_at.empty()) stamped.meta.recorded_at = NowIso8601();
  if (replace) {
    // Keep the old take: hard-link it into trash/ before the new one replaces it atomically.
    fs::create_directories(Path(kTrashFolder));
    fs::create_hard_link(final_path, TrashName(Path(kTrashFolder), name));
  }
  // The rename is the commit; fsync first so that a power loss cannot leave a renamed but empty
  // episode.
  // Open removed the dead writers' temporaries here; a sweep per commit would list the folder
  // (O(episodes)) every time.
  WriteFileVia(
      final_path, Durability::kFsync,
      [&](const std::string& tmp) { WriteDemoFile(tmp, manifest_, stamped); }, /*sweep=*/false);

  EpisodeEntry entry;
  entry.name = name;
  entry.path = final_path;
  entry.number = number;
  entry.meta = stamped.meta;
  if (replace) {
    EpisodeEntry& old = FindMutable(name);
    entry.flags.split = old.flags.split;  // a re-take stays in its split, and is no longer bad
    old = entry;
    manifest_.episode_flags[name] = entry.flags;
    SaveManifestNow();
  } else {
    demos_.push_back(entry);
    highest_demo_number_ = number;
  }
  IndexChanged();
  return Find(name);
}

const EpisodeEntry& Session::CommitPlay(const PlayRecord& record) {
  RequireWritable();
  const int number = NextPlayNumber();
  const std::string name = "play_" + std::to_string(number);
  const std::string final_path = Path(std::string(kPlayFolder) + "/" + name + ".h5");
  PlayRecord stamped = record;
  stamped.meta.kind = "play";
  stamped.meta.num_samples = static_cast<int64_t>(record.samples.size());
  if (stamped.meta.recorded_at.empty()) stamped.meta.recorded_at = NowIso8601();
  WriteFileVia(
      final_path, Durability::kFsync,
      [&](const std::string& tmp) { WritePlayFile(tmp, manifest_, stamped); }, /*sweep=*/false);
  EpisodeEntry entry;
  entry.name = name;
  entry.path = final_path;
  entry.number = number;
  entry.meta = stamped.meta;
  play_.push_back(entry);
  highest_play_number_ = number;
  IndexChanged();
  return play_.back();
}

}  // namespace recon::store
