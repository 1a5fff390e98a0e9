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

#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/rng.h"
#include "engine/store/atomic_file.h"
#include "engine/store/session_index.h"

namespace recon::store {

namespace fs = std::filesystem;

namespace {

constexpr char kManifestName[] = "session.json";
constexpr char kIndexName[] = "session.hdf5";
constexpr char kDemoFolder[] = "episodes";
constexpr char kPlayFolder[] = "play";
constexpr char kTrashFolder[] = "trash";
constexpr char kLockName[] = ".lock";

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

std::string ReadText(const std::string& path) {
  std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError("cannot read " + path);
  return *text;
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
    // Killed writers of checkpoints, training records, rollouts and reports left temporaries.
    for (const char* folder : {"", kCheckpointFolder, kTrainingFolder, kRolloutFolder, "report",
                               "report/figures", kTrashFolder}) {
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

namespace {

std::string TrashName(const fs::path& trash, const std::string& name) {
  fs::path target = trash / (name + ".h5");
  for (int i = 1; fs::exists(target); ++i) {
    target = trash / (name + "." + std::to_string(i) + ".h5");
  }
  return target.string();
}

}  // namespace

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

const EpisodeEntry& Session::Find(const std::string& name) const {
  for (const auto* list : {&demos_, &play_}) {
    for (const EpisodeEntry& e : *list) {
      if (e.name == name) return e;
    }
  }
  std::string known;
  for (const EpisodeEntry& e : demos_) known += (known.empty() ? "" : ", ") + e.name;
  throw UserError("session " + dir_ + " has no episode '" + name + "'" +
                  (known.empty() ? " (it has no demonstrations)" : "; demonstrations: " + known));
}

EpisodeEntry& Session::FindMutable(const std::string& name) {
  return const_cast<EpisodeEntry&>(Find(name));
}

std::string Session::DeleteEpisode(const std::string& name) {
  RequireWritable();
  const EpisodeEntry entry = Find(name);
  fs::create_directories(Path(kTrashFolder));
  const std::string target = TrashName(Path(kTrashFolder), name);
  ReplaceFile(entry.path, target);
  SyncDirectory(Path(kTrashFolder));
  auto& list = name.rfind("demo_", 0) == 0 ? demos_ : play_;
  list.erase(std::remove_if(list.begin(), list.end(),
                            [&](const EpisodeEntry& e) { return e.name == name; }),
             list.end());
  if (manifest_.episode_flags.erase(name) > 0) SaveManifestNow();
  IndexChanged();
  return target;
}

void Session::RestoreEpisode(const std::string& trash_path, const std::string& name,
                             const EpisodeFlags& flags) {
  RequireWritable();
  const bool demo = name.rfind("demo_", 0) == 0;
  const auto& list = demo ? demos_ : play_;
  if (std::any_of(list.begin(), list.end(),
                  [&](const EpisodeEntry& e) { return e.name == name; })) {
    throw UserError("cannot restore " + name + ": the session has an episode of that name again");
  }
  if (!fs::is_regular_file(trash_path)) {
    throw UserError("cannot restore " + name + ": " + trash_path + " is no longer in trash/");
  }
  const std::string folder = Path(demo ? kDemoFolder : kPlayFolder);
  ReplaceFile(trash_path, (fs::path(folder) / (name + ".h5")).string());
  SyncDirectory(folder);
  if (!(flags == EpisodeFlags{})) {
    manifest_.episode_flags[name] = flags;
    SaveManifestNow();
  }
  Scan();  // reads the restored file as Open does (and checks it)
  IndexChanged();
}

void Session::MarkBad(const std::string& name, bool bad) {
  RequireWritable();
  EpisodeEntry& entry = FindMutable(name);
  entry.flags.bad = bad;
  manifest_.episode_flags[name] = entry.flags;
  SaveManifestNow();
  IndexChanged();
}

void Session::SetSplit(const std::string& name, const std::string& split) {
  RequireWritable();
  if (split != "train" && split != "valid") {
    throw UserError("split must be 'train' or 'valid' (got '" + split + "')");
  }
  EpisodeEntry& entry = FindMutable(name);
  if (entry.name.rfind("demo_", 0) != 0)
    throw UserError(name + " is play data, which has no split");
  entry.flags.split = split;
  manifest_.episode_flags[name] = entry.flags;
  SaveManifestNow();
  IndexChanged();
}

void Session::SetNote(const std::string& name, const std::string& note) {
  RequireWritable();
  EpisodeEntry& entry = FindMutable(name);
  entry.flags.note = note;
  manifest_.episode_flags[name] = entry.flags;
  SaveManifestNow();
}

void Session::SetFlags(const std::string& name, const EpisodeFlags& flags) {
  RequireWritable();
  if (flags.split != "train" && flags.split != "valid") {
    throw UserError("split must be 'train' or 'valid' (got '" + flags.split + "')");
  }
  EpisodeEntry& entry = FindMutable(name);
  entry.flags = flags;
  manifest_.episode_flags[name] = flags;
  SaveManifestNow();
  IndexChanged();
}

void Session::AssignSplits(double valid_fraction, uint64_t seed) {
  RequireWritable();
  if (!(valid_fraction >= 0.0 && valid_fraction < 1.0)) {
    throw UserError("the validation fraction must be in [0, 1) (got " +
                    std::to_string(valid_fraction) + ")");
  }
  const size_t n = demos_.size();
  size_t valid = static_cast<size_t>(valid_fraction * static_cast<double>(n) + 0.5);
  if (valid_fraction > 0 && valid == 0 && n >= 2) valid = 1;
  if (valid >= n && n > 0) valid = n - 1;  // keep at least one to train on
  // A seeded Fisher-Yates shuffle of the indices; the first `valid` go to validation.
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  Rng rng(seed);
  for (size_t i = n; i > 1; --i) std::swap(order[i - 1], order[rng.UniformInt(i)]);
  for (size_t i = 0; i < n; ++i) {
    EpisodeEntry& e = demos_[order[i]];
    e.flags.split = i < valid ? "valid" : "train";
    manifest_.episode_flags[e.name] = e.flags;
  }
  SaveManifestNow();
  IndexChanged();
}

void Session::AssignBeacon(const std::string& beacon, const std::string& object) {
  RequireWritable();
  const bool known = std::any_of(manifest_.beacons.begin(), manifest_.beacons.end(),
                                 [&](const BeaconSpec& b) { return b.name == beacon; });
  if (!known) throw UserError("session " + dir_ + " has no beacon '" + beacon + "'");
  manifest_.beacon_assignments[beacon] = object;
  SaveManifestNow();
}

void Session::AttachCalibration(const std::string& calibration_path) {
  RequireWritable();
  calib::LoadCalibration(calibration_path);  // validates before anything is replaced
  WriteFileAtomically(Path("calibration.json"), ReadText(calibration_path));
  manifest_.calibration_file = "calibration.json";
  SaveManifestNow();
}

}  // namespace recon::store
