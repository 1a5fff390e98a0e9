#pragma once

#include <string>
#include <vector>

#include "engine/store/session.h"

namespace recon::store {

/// robomimic's `data.attrs["env_args"]`: JSON naming the environment and how it was configured
/// ({"env_name": "recon/<world>", "type": ..., "env_kwargs": {...}}), so a file says which cell,
/// placement and beacons produced it.
std::string EnvArgsJson(const SessionManifest& manifest);

/// Writes `path` (atomically: temporary file, then rename) as the robomimic view of `session`:
///
///   data                attrs total (samples of the linked demonstrations), env_args
///   data/demo_N         external link to episodes/demo_N.h5 (bad demonstrations left out)
///   play/play_N         external link to play/play_N.h5
///   mask/train, mask/valid   names of the demonstrations in each split (robomimic filter keys)
///
/// Links are relative to the session folder, so the folder can be moved or copied whole; h5py,
/// h5dump and the HDF5 library follow them when the file is opened from anywhere.
void WriteSessionIndex(const Session& session, const std::string& path);

/// True when `path` is an index that WriteSessionIndex wrote for the session as it is now (it
/// stores a fingerprint of what it lists), so opening a session need not rewrite it.
bool SessionIndexIsCurrent(const Session& session, const std::string& path);

}  // namespace recon::store
