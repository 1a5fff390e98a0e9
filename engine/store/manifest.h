#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/core/beacon_spec.h"
#include "engine/core/dataset.h"

namespace recon::store {

/// The manifest format this program writes; it reads this and every older version.
constexpr int kManifestVersion = 1;

/// A device of the cell, as recorded with the session ("simulated" or a real driver's name).
struct DeviceEntry {
  std::string role;    ///< "camera", "arm", "beacons", "teleop"
  std::string kind;    ///< "simulated", "dwm1001", "ur5-rtde", "scripted", ...
  std::string detail;  ///< free text: port, model, resolution

  bool operator==(const DeviceEntry& other) const = default;
};

/// What a teacher can change about an episode after recording it.
struct EpisodeFlags {
  bool bad = false;             ///< left out of training and export, but kept on disk
  std::string split = "train";  ///< "train" or "valid" (robomimic's mask/train, mask/valid)
  std::string note;

  bool operator==(const EpisodeFlags& other) const = default;
};

/// The session's `session.json`: everything about a teaching session that is not an episode's
/// arrays. Episodes themselves are files under episodes/ and play/ (see Session); the manifest
/// holds only their mutable flags, so committing an episode never has to rewrite it.
struct SessionManifest {
  int version = kManifestVersion;
  std::string created_at;  ///< ISO 8601 UTC
  std::string created_by;  ///< "recon 0.1.0"

  // The cell.
  std::string world;               ///< "tabletop", "bintransfer", "dynamic2d", "static2d", ...
  std::string cell = "simulated";  ///< "simulated" or "real"
  std::string placement;           ///< the world's beacon placement while teaching
  /// The world's scene layout ("paper" or "wide" for tabletop; empty for worlds without layouts).
  std::string layout;
  double beacon_noise_sigma = 0;
  /// Noise injected into the executed arm motion while demonstrating (worlds::DemoNoise), in the
  /// action's units; 0 = off. The teacher's commands are the labels either way.
  double demo_noise_sigma = 0;
  int image_size = 0;       ///< camera images are image_size x image_size (0: none)
  double step_seconds = 0;  ///< control period of a demonstration step
  std::vector<DeviceEntry> devices;
  std::vector<BeaconSpec> beacons;  ///< in the order their readings form b
  DataSpec spec;                    ///< shapes every episode must have
  /// How y is stored: "uint8" (camera images, HWC, as robomimic expects) or "float32".
  std::string y_encoding = "float32";

  /// The calibration file in the session folder ("calibration.json"), empty if none.
  std::string calibration_file;

  uint64_t seed = 1;  ///< scenario seeds of new episodes derive from this and their number
  /// Seconds a teacher spends sticking one beacon on and taking it off again (the paper's
  /// measured 2.3 s each, twice per beacon), for the teaching-time ledger.
  double seconds_per_beacon_placement = 2.3;
  int placements_per_beacon = 2;
  /// The teacher's time that no kept episode shows: takes discarded or recorded over (their
  /// recorded seconds), and the waits before a person's takes (the countdown, or the arm's way
  /// home when that is longer). Absent in older sessions: 0.
  int discarded_takes = 0;
  double discarded_seconds = 0;
  double countdown_seconds = 0;
  /// The teleop the teacher chose last in the studio ("scripted", "keyboard", "gamepad"), which a
  /// reopened session starts with; empty: the studio's default.
  std::string teleop;

  std::map<std::string, EpisodeFlags> episode_flags;  ///< by episode name; absent = defaults
  /// Which object the teacher says each beacon is stuck on (beacon name -> object name), set in
  /// the studio's Beacons step. Absent for sessions recorded from the command line, whose
  /// beacons are where the task puts them (BeaconSpec::object).
  std::map<std::string, std::string> beacon_assignments;

  bool operator==(const SessionManifest& other) const = default;
};

/// The manifest as JSON text (stable key order, indented).
std::string ManifestToJson(const SessionManifest& manifest);

/// Parses a manifest. Throws UserError naming `source` and the missing or wrong field, or a
/// version newer than kManifestVersion.
SessionManifest ManifestFromJson(const std::string& text, const std::string& source);

/// Reads and parses a manifest file (UserError naming the path when unreadable).
SessionManifest LoadManifest(const std::string& path);
/// Writes the manifest atomically.
void SaveManifest(const SessionManifest& manifest, const std::string& path);

}  // namespace recon::store
