#include "engine/store/session.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <tuple>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/rng.h"
#include "engine/store/atomic_file.h"
#include "engine/store/session_index.h"
#include "engine/store/session_layout.h"

namespace recon::store {

namespace fs = std::filesystem;

namespace {

/// The N of "<prefix>N.h5" (or "<prefix>N.<anything>.h5" in trash/), or -1.
int EpisodeNumber(const std::string& file_name, const std::string& prefix) {
  if (file_name.rfind(prefix, 0) != 0) return -1;
  size_t end = prefix.size();
  while (end < file_name.size() && std::isdigit(static_cast<unsigned char>(file_name[end]))) ++end;
  if (end == prefix.size() || end - prefix.size() > 9) return -1;
  const std::string rest = file_name.substr(end);
  if (rest != ".h5" && rest.rfind('.', 0) != 0) return -1;
  if (rest.size() < 3 || rest.substr(rest.size() - 3) != ".h5") return -1;
  return std::stoi(file_name.substr(prefix.size(), end - prefix.size()));
}

bool IsTemporary(const std::string& file_name) {
  return file_name.find(".tmp.") != std::string::npos;
}

/// Committed episode files (demo_N.h5, play_N.h5) in `dir`'s episode folders.
int CountEpisodeFiles(const std::string& dir) {
  int count = 0;
  std::error_code ec;
  for (const auto& [folder, prefix] :
       {std::pair{kDemoFolder, "demo_"}, std::pair{kPlayFolder, "play_"}}) {
    const fs::path folder_path = fs::path(dir) / folder;
    if (!fs::is_directory(folder_path, ec)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_path, ec)) {
      if (EpisodeNumber(entry.path().filename().string(), prefix) >= 0) ++count;
    }
  }
  return count;
}

// An episode file that cannot be opened or disagrees with the manifest is listed, not fatal:
// the other episodes stay usable, and the damaged one is named when it would be used.
struct Inspection {
  EpisodeMeta meta;
  std::string problem;
};

Inspection Inspect(const std::string& path, const SessionManifest& layout,
                   const std::string& kind) {
  Inspection result;
  try {
    result.meta = ReadEpisodeMeta(path);
    if (result.meta.kind != kind) {
      throw UserError(path + ": attribute 'recon_kind' is \"" + result.meta.kind + "\" in the " +
                      kind + " folder");
    }
    CheckEpisodeShapes(path, layout, result.meta);
  } catch (const UserError& e) {
    result.problem = e.what();
  }
  return result;
}

}  // namespace

Session Session::Create(const std::string& dir, const SessionManifest& manifest) {
  if (Exists(dir)) {
    throw UserError(dir + " already holds a teaching session (" + kManifestName +
                    "); open it to append, or choose another folder");
  }
  std::error_code ec;
  const bool existed = fs::exists(dir, ec);
  if (existed && fs::is_directory(dir, ec) && !fs::is_empty(dir, ec)) {
    // A session whose manifest was lost still holds the teacher's episodes: a new session here
    // would number its takes from demo_0 again and replace them.
    const int episodes = CountEpisodeFiles(dir);
    if (episodes > 0) {
      throw UserError(dir + " holds " + std::to_string(episodes) + " episode file(s) but no " +
                      kManifestName +
                      ": its manifest is missing. Nothing was changed. Rebuild the manifest "
                      "with `recon session repair " +
                      dir +
                      " --world W` (W the world it was recorded in), or choose another "
                      "folder");
    }
    throw UserError(dir + " is not empty and holds no teaching session (no " + kManifestName +
                    "); a new session needs a new or empty folder. Nothing was changed");
  }
  EnsureWritableDirectory(dir);
  try {
    return CreateIn(dir, manifest);
  } catch (...) {
    // A half-made session would be taken for a real one by the next command: undo it.
    if (!existed) {
      fs::remove_all(dir, ec);
    } else {
      for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
        fs::remove_all(entry.path(), ec);
      }
    }
    throw;
  }
}

Session Session::CreateIn(const std::string& dir, const SessionManifest& manifest) {
  Session session;
  session.dir_ = dir;
  session.manifest_ = manifest;
  session.access_ = Access::kReadWrite;
  session.RequireWritable();
  fs::create_directories(session.Path(kDemoFolder));
  fs::create_directories(session.Path(kPlayFolder));
  session.SaveManifestNow();
  session.RebuildIndex();
  return session;
}

Session Session::Repair(const std::string& dir, SessionManifest manifest) {
  if (Exists(dir)) {
    throw UserError(dir + " has its " + kManifestName + "; there is nothing to repair");
  }
  if (!fs::is_directory(dir) || CountEpisodeFiles(dir) == 0) {
    throw UserError(dir +
                    " holds no episode files (episodes/demo_N.h5, play/play_N.h5); there "
                    "is no session to repair there");
  }
  Session session;
  session.dir_ = dir;
  session.manifest_ = manifest;
  session.access_ = Access::kReadWrite;
  session.RequireWritable();
  // The episodes must agree with the manifest given, or the repair would make a session whose
  // episodes all read as damaged: check them before writing anything. One that cannot be read
  // (a truncated file) does not block the others: it stays listed as damaged, as in any session.
  session.Scan();
  std::string earliest, first_problem;
  int agreeing = 0;
  for (const std::vector<EpisodeEntry>* list : {&session.demos_, &session.play_}) {
    for (const EpisodeEntry& e : *list) {
      if (!e.problem.empty()) {
        if (first_problem.empty()) first_problem = e.problem;
        continue;
      }
      ++agreeing;
      if (earliest.empty() || e.meta.recorded_at < earliest) earliest = e.meta.recorded_at;
    }
  }
  if (agreeing == 0) {
    throw UserError("cannot repair " + dir + " as a " + manifest.world + " session: no episode " +
                    "agrees with it (" + first_problem + "). Nothing was changed");
  }
  if (!earliest.empty()) session.manifest_.created_at = earliest;
  if (fs::exists(session.Path("calibration.json"))) {
    session.manifest_.calibration_file = "calibration.json";
  }
  session.SaveManifestNow();
  session.RebuildIndex();
  return session;
}

Session Session::Open(const std::string& dir, Access access) {
  const std::string manifest_path = (fs::path(dir) / kManifestName).string();
  if (!fs::exists(manifest_path)) {
    throw UserError(dir + " is not a teaching session (it has no " + kManifestName + ")");
  }
  Session session;
  session.dir_ = dir;
  session.manifest_ = LoadManifest(manifest_path);
  session.access_ = access;
  if (access == Access::kReadWrite) session.RequireWritable();
  session.Scan();
  if (access == Access::kReadWrite) {
    // Killed writers of checkpoints, training records, rollouts, trials, probes and reports left
    // temporaries.
    for (const char* folder : {"", kCheckpointFolder, kTrainingFolder, kRolloutFolder, kTrialFolder,
                               kProbeFolder, "report", "report/figures", kTrashFolder}) {
      session.recovered_temporaries_ += RemoveDeadTemporariesIn(session.Path(folder));
    }
  }
  // A killed writer may have left the index behind the episode files: bring it up to date.
  if (access == Access::kReadWrite && !SessionIndexIsCurrent(session, session.Path(kIndexName))) {
    session.RebuildIndex();
  }
  return session;
}

bool Session::Exists(const std::string& dir) { return fs::exists(fs::path(dir) / kManifestName); }

Session::Session(Session&& other) noexcept { *this = std::move(other); }

Session& Session::operator=(Session&& other) noexcept {
  if (this != &other) {
    if (lock_fd_ >= 0) ::close(lock_fd_);
    dir_ = std::move(other.dir_);
    manifest_ = std::move(other.manifest_);
    demos_ = std::move(other.demos_);
    play_ = std::move(other.play_);
    access_ = other.access_;
    lock_fd_ = other.lock_fd_;
    recovered_temporaries_ = other.recovered_temporaries_;
    highest_demo_number_ = other.highest_demo_number_;
    highest_play_number_ = other.highest_play_number_;
    index_deferred_ = other.index_deferred_;
    index_stale_ = other.index_stale_;
    other.lock_fd_ = -1;
  }
  return *this;
}

Session::~Session() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
}

std::string Session::Path(const std::string& relative) const {
  return (fs::path(dir_) / relative).string();
}

void Session::RequireWritable() const {
  if (access_ != Access::kReadWrite) {
    throw UserError("session " + dir_ + " was opened read-only");
  }
  if (lock_fd_ >= 0) return;
  // Checked before anything is recorded, so a teacher never demonstrates into a folder that
  // cannot keep the result.
  try {
    EnsureWritableDirectory(dir_);
  } catch (const UserError& e) {
    throw UserError("session folder " + dir_ + " is not writable (" + e.what() +
                    "): check its permissions; nothing was changed");
  }
  const std::string lock_path = Path(kLockName);
  const int fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw UserError("session folder " + dir_ + " is not writable: cannot create " + lock_path +
                    " (" + std::strerror(errno) + ")");
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw UserError("session " + dir_ +
                    " is being written by another process (recording or editing); wait for it "
                    "to finish");
  }
  const_cast<Session*>(this)->lock_fd_ = fd;
}

void Session::Scan() {
  demos_.clear();
  play_.clear();
  highest_demo_number_ = highest_play_number_ = -1;
  const bool writable = access_ == Access::kReadWrite;
  for (const auto& [folder, prefix, kind, list] :
       {std::tuple{kDemoFolder, "demo_", "demo", &demos_},
        std::tuple{kPlayFolder, "play_", "play", &play_}}) {
    const fs::path folder_path = Path(folder);
    if (!fs::is_directory(folder_path)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_path)) {
      const std::string file_name = entry.path().filename().string();
      if (IsTemporary(file_name)) {
        // An episode that was being written when its writer died: it was never committed.
        if (writable) {
          std::error_code ignored;
          fs::remove(entry.path(), ignored);
          ++recovered_temporaries_;
        }
        continue;
      }
      const int number = EpisodeNumber(file_name, prefix);
      if (number < 0 || file_name != prefix + std::to_string(number) + ".h5") continue;
      EpisodeEntry e;
      e.name = prefix + std::to_string(number);
      e.path = entry.path().string();
      e.number = number;
      const Inspection inspection = Inspect(e.path, manifest_, kind);
      e.meta = inspection.meta;
      e.problem = inspection.problem;
      if (auto it = manifest_.episode_flags.find(e.name); it != manifest_.episode_flags.end()) {
        e.flags = it->second;
      }
      list->push_back(e);
    }
    std::sort(list->begin(), list->end(),
              [](const EpisodeEntry& a, const EpisodeEntry& b) { return a.number < b.number; });
    int& highest = list == &demos_ ? highest_demo_number_ : highest_play_number_;
    for (const EpisodeEntry& e : *list) highest = std::max(highest, e.number);
  }
  // Deleted episodes keep their numbers: a name is never given to different data.
  if (fs::is_directory(Path(kTrashFolder))) {
    for (const fs::directory_entry& entry : fs::directory_iterator(Path(kTrashFolder))) {
      const std::string file_name = entry.path().filename().string();
      highest_demo_number_ = std::max(highest_demo_number_, EpisodeNumber(file_name, "demo_"));
      highest_play_number_ = std::max(highest_play_number_, EpisodeNumber(file_name, "play_"));
    }
  }
}

int64_t Session::PlaySamples() const {
  int64_t total = 0;
  for (const EpisodeEntry& e : play_) total += e.meta.num_samples;
  return total;
}

int Session::NextDemoNumber() const { return highest_demo_number_ + 1; }
int Session::NextPlayNumber() const { return highest_play_number_ + 1; }

uint64_t Session::ScenarioSeed(uint64_t seed, int number, bool play) {
  return Rng::Derive(Rng::Derive(seed, play ? 2 : 1), static_cast<uint64_t>(number));
}

void Session::SaveManifestNow() const { SaveManifest(manifest_, Path(kManifestName)); }

void Session::RebuildIndex() const {
  RequireWritable();
  WriteSessionIndex(*this, Path(kIndexName));
}

void Session::DeferIndex(bool defer) {
  index_deferred_ = defer;
  if (!defer && index_stale_) {
    RebuildIndex();
    index_stale_ = false;
  }
}

void Session::IndexChanged() {
  if (index_deferred_) {
    index_stale_ = true;
  } else {
    RebuildIndex();
  }
}

}  // namespace recon::store
