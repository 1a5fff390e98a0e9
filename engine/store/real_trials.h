#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/store/session.h"

namespace recon::store {

/// One trial of a trained policy on a real arm, as a lab runs it: a person sets the test layout
/// up, the policy runs (through the safety envelope) until its time is up or the person stops
/// it, and the person judges it.
struct RealTrial {
  int number = 0;           ///< 1, 2, ... within its method's log
  uint64_t scene_seed = 0;  ///< the test scene whose layout was set up (the simulated rollouts')
  /// Where the person was asked to put each object: table x, y in metres, by object.
  std::map<std::string, std::array<double, 2>> layout;
  bool succeeded = false;
  std::string reason;    ///< the person's words ("missed the toast"); may be empty for a success
  bool stopped = false;  ///< stopped by the person before the time limit
  int steps = 0;
  double seconds = 0;
  /// The camera frames the policy saw, relative to the session (Session::TrialFramesRelativePath).
  std::optional<std::string> frames;
  std::string judged_at;  ///< ISO 8601 UTC

  bool operator==(const RealTrial& other) const = default;
};

/// trials/<method>.json (Session::RealTrialsPath): the trials of a method's policy on the real
/// arm, appended to as each is judged, so a session keeps every judged trial whatever happens to
/// the next one.
struct RealTrialLog {
  std::string method;  ///< "baseline" or "recon" (default: the file's name)
  std::string label;   ///< as its training record's (default: the method)
  /// The model the trials ran (TrainingRecord::model_id), none when it had no training record.
  std::optional<std::string> model_id;
  /// The cell the trials ran on and its devices ("real (camera: ..., arm: ...)"); the session
  /// itself may have been taught in the simulated cell.
  std::string cell;
  std::vector<RealTrial> trials;

  int successes() const;
  double success_rate() const;  ///< 0 without trials
  bool operator==(const RealTrialLog& other) const = default;
};

nlohmann::json RealTrialLogToJson(const RealTrialLog& log);
/// UserError naming `source` and the field for a value of the wrong kind, a trial numbered out
/// of order or a frames path outside the session.
RealTrialLog RealTrialLogFromJson(const nlohmann::json& value, const std::string& source,
                                  const std::string& method);
/// Writes the log to `path` atomically.
void WriteRealTrialLog(const std::string& path, const RealTrialLog& log);
/// The method's trials on a real arm, nullopt when it has none.
std::optional<RealTrialLog> ReadRealTrialLog(const Session& session, const std::string& method);
/// Every method's, by method.
std::map<std::string, RealTrialLog> ReadRealTrialLogs(const Session& session);

/// What the policy saw and did in one trial, for playing it back: the observations' robot
/// state x and camera image y (the policy's S x S view, channels first, 0-255) and the actions
/// u, one row per step.
struct TrialFrames {
  int image_size = 0;
  std::vector<std::vector<float>> x, y, u;
};
/// Writes the frames to an HDF5 file (checksummed datasets, the image as bytes) atomically.
/// UserError for rows of differing sizes or an image that is not 3 x S x S.
void WriteTrialFrames(const std::string& path, const TrialFrames& frames);
/// UserError naming the file for one that is missing, damaged or not a trial's frames.
TrialFrames ReadTrialFrames(const std::string& path);

}  // namespace recon::store
