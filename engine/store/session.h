#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/store/episode_file.h"
#include "engine/store/manifest.h"

namespace recon::store {

/// A committed episode as the session lists it.
struct EpisodeEntry {
  std::string name;  ///< "demo_7" or "play_2"
  std::string path;  ///< its file
  EpisodeMeta meta;
  EpisodeFlags flags;
  int number = 0;  ///< the N of demo_N / play_N
  /// Why the file cannot be used (unreadable, or shapes that disagree with the manifest); empty
  /// when it is fine. A damaged episode is listed, never used, and can be deleted.
  std::string problem;
};

/// Which demonstrations a dataset is built from.
enum class Split { kAll, kTrain, kValid };

struct DatasetOptions {
  Split split = Split::kTrain;
  bool include_bad = false;  ///< bad episodes are left out unless asked
  bool include_play = true;  ///< play chunks (never split, never bad)
};

/// A teaching session: a folder holding
///
///   session.json        the manifest (manifest.h), replaced atomically
///   episodes/demo_N.h5  one file per demonstration (episode_file.h)
///   play/play_N.h5      one file per chunk of play data
///   session.hdf5        the robomimic view: data/demo_N and play/play_N linked to the files above,
///                       mask/train and mask/valid; rebuilt after every change (session_index.h)
///   calibration.json    the beacon calibration, if one was attached
///   checkpoints/, training/, rollouts/, report/, trash/
///
/// Crash safety: an episode is written to a temporary file and renamed into place; the rename is
/// the commit. A process killed at any moment leaves every committed episode intact and at most
/// a temporary file, which the next writer removes. Nothing else has to be consistent with the
/// episode files: the index is derived from them and rebuilt when stale, and the manifest only
/// holds flags. One process writes a session at a time (an advisory lock, released by the kernel
/// when the process dies, however it dies).
class Session {
 public:
  enum class Access { kReadOnly, kReadWrite };

  /// Makes a new session in `dir`, which must be new or empty. UserError if the folder cannot
  /// be written, holds a session, or holds anything else (episode files without a manifest are
  /// a damaged session: see Repair). If creating fails part-way, what it made is removed.
  static Session Create(const std::string& dir, const SessionManifest& manifest);
  /// Gives a session that lost its session.json a new one: `manifest` describes the world the
  /// episodes were recorded in (as Create would get it); the episode files must agree with it
  /// (shapes, kinds): if none does, UserError naming the first file's problem and nothing is
  /// written; unreadable ones among good ones stay listed as damaged. The episodes' flags
  /// (bad, split, notes) were in the lost manifest and come back as defaults; the creation time
  /// is the earliest episode's, and calibration.json is attached if present.
  static Session Repair(const std::string& dir, SessionManifest manifest);
  /// Opens an existing session. kReadWrite also takes the writer lock, removes temporary files
  /// left by a killed writer (counted in recovered_temporaries()) and rebuilds a stale index.
  /// UserError naming the file and field for a missing or corrupt manifest, an episode file that
  /// cannot be read, or an episode whose shapes disagree with the manifest.
  static Session Open(const std::string& dir, Access access = Access::kReadWrite);
  /// True when `dir` holds a session manifest.
  static bool Exists(const std::string& dir);

  Session(Session&&) noexcept;
  Session& operator=(Session&&) noexcept;
  ~Session();

  const std::string& dir() const { return dir_; }
  const SessionManifest& manifest() const { return manifest_; }
  const std::vector<EpisodeEntry>& demos() const { return demos_; }
  const std::vector<EpisodeEntry>& play_chunks() const { return play_; }
  int64_t PlaySamples() const;
  /// Temporary files of interrupted commits removed when the session was opened.
  int recovered_temporaries() const { return recovered_temporaries_; }

  /// The number the next demonstration gets (one past every demonstration ever committed,
  /// deleted ones included, so a name is never reused).
  int NextDemoNumber() const;
  int NextPlayNumber() const;
  /// The scenario seed of demonstration (or play chunk) number `number` under `seed`.
  static uint64_t ScenarioSeed(uint64_t seed, int number, bool play);

  /// Commits a demonstration atomically as the next demo_N, or in place of `replace` (re-record:
  /// the old episode moves to trash/ only once the new one is committed). Returns its entry.
  const EpisodeEntry& CommitDemo(const DemoRecord& record,
                                 const std::optional<std::string>& replace = std::nullopt);
  const EpisodeEntry& CommitPlay(const PlayRecord& record);

  /// Moves an episode's file to trash/ and returns where it went (RestoreEpisode takes it back).
  /// UserError for an unknown name.
  std::string DeleteEpisode(const std::string& name);
  /// Undoes DeleteEpisode: moves `trash_path` back as episode `name` with its `flags`. UserError
  /// when the file is gone from trash/ or `name` is taken again.
  void RestoreEpisode(const std::string& trash_path, const std::string& name,
                      const EpisodeFlags& flags);
  void MarkBad(const std::string& name, bool bad);
  void SetSplit(const std::string& name, const std::string& split);
  /// Assigns `valid_fraction` of the demonstrations (at least one if the fraction is positive
  /// and there are two or more) to validation, drawn with `seed`; the rest to training.
  void AssignSplits(double valid_fraction, uint64_t seed);
  /// Records which object beacon `beacon` is stuck on. UserError for an unknown beacon.
  void AssignBeacon(const std::string& beacon, const std::string& object);
  /// The teaching-time ledger's share that no kept episode shows: a take discarded or recorded
  /// over (`seconds` recorded), or a wait before a person's take (`countdown_seconds`: the
  /// countdown, or the arm's way home beyond it).
  void AddUnkeptTime(int takes, double seconds, double countdown_seconds);
  /// The teleop the teacher chose ("scripted", "keyboard", "gamepad"), kept for the next time the
  /// session is opened.
  void RememberTeleop(const std::string& teleop);
  /// Records the calibration file (copied into the session as calibration.json).
  void AttachCalibration(const std::string& calibration_path);
  void SetNote(const std::string& name, const std::string& note);
  /// Sets all of an episode's flags at once (imports).
  void SetFlags(const std::string& name, const EpisodeFlags& flags);

  const EpisodeEntry& Find(const std::string& name) const;
  DemoRecord ReadDemo(const std::string& name) const;
  PlayRecord ReadPlay(const std::string& name) const;
  /// Loads demonstrations (and play) into a training dataset. Episodes are read in number order.
  Dataset LoadDataset(const DatasetOptions& options = {}) const;
  /// The episodes LoadDataset(options) reads, by name in order: demonstrations, then play
  /// chunks. A model records them, so the session can tell when the data it would train on has
  /// changed since (an episode recorded, deleted, marked bad or moved between splits).
  std::vector<std::string> DatasetEpisodeNames(const DatasetOptions& options = {}) const;

  /// Where a method's ("baseline", "recon") results live: its model, what training it recorded
  /// (training_record.h), the summary of its rollouts (rollout_summary.h) and their step-by-step
  /// replay (rollout_replay.h). Every reader and writer of these files asks here.
  std::string CheckpointPath(const std::string& method) const;
  std::string TrainingRecordPath(const std::string& method) const;
  std::string RolloutSummaryPath(const std::string& method) const;
  std::string RolloutReplayPath(const std::string& method) const;
  /// The same files relative to the session folder, as the records name them
  /// ("checkpoints/recon.ckpt").
  static std::string CheckpointRelativePath(const std::string& method);
  static std::string TrainingRecordRelativePath(const std::string& method);
  static std::string RolloutSummaryRelativePath(const std::string& method);
  static std::string RolloutReplayRelativePath(const std::string& method);
  /// A method's trials on a real arm (real_trials.h) and the camera frames of trial `number`.
  std::string RealTrialsPath(const std::string& method) const;
  std::string TrialFramesPath(const std::string& method, int number) const;
  static std::string TrialFramesRelativePath(const std::string& method, int number);
  /// What the distractor probe found of the trained methods (engine/store/probe_summary.h), and
  /// the heat map of each method and object it moved.
  std::string ProbeSummaryPath() const;
  static std::string ProbeFigureRelativePath(const std::string& method, const std::string& object);
  std::string ProbeFigurePath(const std::string& method, const std::string& object) const;
  /// The saliency sheet of a recorded demonstration (`recon eval --saliency demo_N`).
  std::string SaliencySheetPath(const std::string& episode) const;
  /// The folders holding them.
  static constexpr char kProbeFolder[] = "probe";
  static constexpr char kCheckpointFolder[] = "checkpoints";
  static constexpr char kTrainingFolder[] = "training";
  static constexpr char kRolloutFolder[] = "rollouts";
  static constexpr char kTrialFolder[] = "trials";
  /// Where the session's own report goes (`recon report`, the studio) and its page in there:
  /// report/report.html.
  std::string ReportFolder() const;
  std::string ReportPath() const;

  /// Rebuilds session.hdf5 (atomically).
  void RebuildIndex() const;
  /// While deferred, commits skip rebuilding session.hdf5 (which lists every episode, so
  /// rebuilding it per commit costs O(episodes)); ending the deferral rebuilds it once. A long
  /// recording defers it; a reader of session.hdf5 then sees the episodes of the last rebuild
  /// (the episode files themselves are always current). A killed writer's stale index is
  /// rebuilt by the next read-write Open.
  void DeferIndex(bool defer);
  /// Teacher seconds of the committed demonstrations and play data.
  double DemoSeconds(bool include_bad = true) const;
  double PlaySeconds() const;

 private:
  Session() = default;
  static Session CreateIn(const std::string& dir, const SessionManifest& manifest);
  void RequireWritable() const;
  void Scan();
  void SaveManifestNow() const;
  std::string Path(const std::string& relative) const;
  EpisodeEntry& FindMutable(const std::string& name);
  void IndexChanged();

  std::string dir_;
  SessionManifest manifest_;
  std::vector<EpisodeEntry> demos_;
  std::vector<EpisodeEntry> play_;
  Access access_ = Access::kReadOnly;
  int lock_fd_ = -1;
  int recovered_temporaries_ = 0;
  int highest_demo_number_ = -1;  ///< including trash/
  int highest_play_number_ = -1;
  bool index_deferred_ = false;
  bool index_stale_ = false;
};

}  // namespace recon::store
