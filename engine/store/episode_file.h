#pragma once

// One recorded episode (a demonstration or a chunk of play data) as one HDF5 file, laid out as a
// robomimic demo group at the file's root (REFERENCE.md 7):
//
//   /                attrs num_samples, recon_kind, recon_seed, recon_source, recon_recorded_at,
//                          recon_teaching_seconds, recon_succeeded
//   /obs/robot_state       float32 (N, x_dim)      the robot state x
//   /obs/camera_image      uint8 (N, H, W, C)      y when it is a camera image (float32 if the
//                                                  session stores y as float32)
//   /obs/environment       float32 (N, m)          y when it is a vector
//   /obs/beacon_<name>     float32 (N, d)          one dataset per beacon
//   /actions               float32 (N, u_dim)      demonstrations only
//   /rewards               float64 (N,)            1 where the task is done, else 0
//   /dones                 int64 (N,)              1 at the last sample
//   /states                float32 (N, x_dim)      robomimic's simulator state: our robot state
//
// The session's index file links these roots in as data/demo_N (see session_index.h). An episode
// file is written whole to a temporary name and renamed: it exists complete or not at all.

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/store/h5.h"
#include "engine/store/manifest.h"

namespace recon::store {

inline constexpr char kRobotStateKey[] = "robot_state";
inline constexpr char kCameraImageKey[] = "camera_image";
inline constexpr char kEnvironmentKey[] = "environment";
/// The obs key of a beacon's readings: "beacon_<name>".
std::string BeaconKey(const std::string& beacon_name);
/// The obs key that holds y under a session's layout.
std::string ObservationKey(const SessionManifest& layout);

/// Facts about an episode stored with it (immutable once committed).
struct EpisodeMeta {
  std::string kind;  ///< "demo" or "play"
  int64_t num_samples = 0;
  uint64_t seed = 0;            ///< the scenario seed (0 when unknown, e.g. imported)
  std::string source;           ///< "scripted-teleop", "keyboard-teleop", "import:<file>", ...
  std::string recorded_at;      ///< ISO 8601 UTC
  double teaching_seconds = 0;  ///< teacher time the episode cost
  bool succeeded = false;       ///< the task was done at the end (demonstrations)
};

/// A demonstration with its facts. rewards has one entry per sample (1 where the task is done).
struct DemoRecord {
  EpisodeMeta meta;
  Episode episode;
  std::vector<double> rewards;
};

/// A chunk of play data with its facts.
struct PlayRecord {
  EpisodeMeta meta;
  std::vector<PlaySample> samples;
};

/// Writes `record` to `path` (creating or truncating it) in the layout above. Checks every
/// sample against layout.spec first and throws UserError naming the sample and field.
void WriteDemoFile(const std::string& path, const SessionManifest& layout,
                   const DemoRecord& record);
void WritePlayFile(const std::string& path, const SessionManifest& layout,
                   const PlayRecord& record);

/// Reads only the attributes (fast: no arrays). UserError naming the file and field.
EpisodeMeta ReadEpisodeMeta(const std::string& path);
/// Checks the shapes of every dataset of an episode file against the layout without reading
/// the arrays (cheap enough to run on every episode when a session opens). UserError naming the
/// file and the dataset.
void CheckEpisodeShapes(const std::string& path, const SessionManifest& layout,
                        const EpisodeMeta& meta);
/// Reads a whole episode and checks its shapes against layout.spec: UserError naming the file and
/// the dataset whose shape disagrees (e.g. a beacon of another size than the session's).
DemoRecord ReadDemoFile(const std::string& path, const SessionManifest& layout);
PlayRecord ReadPlayFile(const std::string& path, const SessionManifest& layout);

/// The same layout inside a group of a bigger file (robomimic's data/demo_N in an export).
/// `next_obs` also writes robomimic's next_obs group (each step's following observation).
void WriteDemoGroup(const h5::File& file, hid_t group, const SessionManifest& layout,
                    const DemoRecord& record, bool next_obs);
void WritePlayGroup(const h5::File& file, hid_t group, const SessionManifest& layout,
                    const PlayRecord& record);
EpisodeMeta ReadEpisodeMeta(const h5::File& file, hid_t group);
DemoRecord ReadDemoGroup(const h5::File& file, hid_t group, const SessionManifest& layout);
PlayRecord ReadPlayGroup(const h5::File& file, hid_t group, const SessionManifest& layout);

/// ISO 8601 UTC time of now, e.g. "2026-11-22T09:30:00Z".
std::string NowIso8601();

}  // namespace recon::store
