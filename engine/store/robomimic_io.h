#pragma once

#include <string>
#include <vector>

#include "engine/store/session.h"

namespace recon::store {

struct ExportOptions {
  bool include_bad = false;  ///< bad demonstrations are left out unless asked
  bool include_play = true;  ///< play chunks under /play (robomimic ignores the group)
  bool next_obs = true;      ///< robomimic's next_obs groups (its loaders read them by default)
};

struct ExportSummary {
  int demos = 0;
  int64_t samples = 0;
  int play_chunks = 0;
  int64_t play_samples = 0;
};

/// Writes one self-contained robomimic HDF5 file (REFERENCE.md 7): data/demo_N with obs,
/// next_obs, actions, rewards, dones, states and num_samples; data.attrs total and env_args;
/// mask/train and mask/valid; play data under /play. The session's manifest is kept as the root
/// attribute `recon_manifest`, so importing the file gives back the same session: its settings,
/// episodes with their data, seeds and flags (bad, split, note), and play data; demonstrations
/// are renumbered from demo_0 in order (a session's names may have gaps). Written to a
/// temporary file and renamed: an existing file at `path` is replaced only by a complete one.
ExportSummary ExportRobomimic(const Session& session, const std::string& path,
                              const ExportOptions& options = {});

/// How to read a robomimic file that RECON Studio did not write: which obs keys form the robot
/// state x (concatenated, in order), which one is the observation y (an image (N, H, W, C) or a
/// vector), and which are beacon readings (each becomes a beacon named after its key).
struct ImportMapping {
  std::vector<std::string> x_keys;
  std::string y_key;
  std::vector<std::string> beacon_keys;
};

struct ImportSummary {
  int demos = 0;
  int64_t samples = 0;
  int64_t play_samples = 0;
  bool from_recon = false;  ///< the file carried a RECON Studio manifest
};

/// Creates a new session in `session_dir` from a robomimic file. A file exported by RECON Studio
/// needs no mapping; any other needs one (UserError listing the file's obs keys otherwise).
/// Every demonstration is checked before the session is created, so a bad file leaves nothing
/// behind; errors name the file, the demonstration and the dataset.
ImportSummary ImportRobomimic(const std::string& path, const std::string& session_dir,
                              const ImportMapping& mapping = {});

/// The obs keys of a robomimic file's first demonstration with their shapes, e.g.
/// "agentview_image (84, 84, 3) uint8", for help texts and error messages.
std::vector<std::string> DescribeObsKeys(const std::string& path);

}  // namespace recon::store
