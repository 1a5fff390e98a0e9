// A session's episodes after they are committed: finding them, deleting (to the trash) and
// restoring them, their marks (bad, split, note), and what the manifest records of the cell
// (beacon assignments, the calibration).

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/rng.h"
#include "engine/store/atomic_file.h"
#include "engine/store/session.h"
#include "engine/store/session_layout.h"

namespace recon::store {

namespace fs = std::filesystem;

namespace {

std::string ReadText(const std::string& path) {
  std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError("cannot read " + path);
  return *text;
}

}  // namespace

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

void Session::AddUnkeptTime(int takes, double seconds, double countdown_seconds) {
  RequireWritable();
  if (takes < 0 || !(seconds >= 0) || !(countdown_seconds >= 0)) {
    throw std::invalid_argument("AddUnkeptTime: counts and seconds must be >= 0");
  }
  manifest_.discarded_takes += takes;
  manifest_.discarded_seconds += seconds;
  manifest_.countdown_seconds += countdown_seconds;
  SaveManifestNow();
}

void Session::RememberTeleop(const std::string& teleop) {
  RequireWritable();
  if (teleop != "scripted" && teleop != "keyboard" && teleop != "gamepad") {
    throw UserError("unknown teleop '" + teleop + "' (valid: scripted, keyboard, gamepad)");
  }
  if (manifest_.teleop == teleop) return;
  manifest_.teleop = teleop;
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
