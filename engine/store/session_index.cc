#include "engine/store/session_index.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "engine/core/digest.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/store/atomic_file.h"
#include "engine/store/h5.h"

namespace recon::store {

namespace fs = std::filesystem;

std::string EnvArgsJson(const SessionManifest& m) {
  nlohmann::json beacons = nlohmann::json::array();
  for (const BeaconSpec& b : m.beacons) {
    beacons.push_back({{"name", b.name}, {"object", b.object}, {"dim", b.dim}, {"unit", b.unit}});
  }
  // robomimic's EnvType has no entry for a RECON cell; 2 (gym-like) is the closest meaning: an
  // environment built by name from env_kwargs. robomimic needs env_args only to make rollout
  // environments; training on the file reads the arrays alone.
  const nlohmann::json args = {{"env_name", "recon/" + m.world},
                               {"type", 2},
                               {"env_kwargs",
                                {{"world", m.world},
                                 {"cell", m.cell},
                                 {"placement", m.placement},
                                 {"beacon_noise_sigma", m.beacon_noise_sigma},
                                 {"image_size", m.image_size},
                                 {"control_period_s", m.step_seconds},
                                 {"beacons", beacons},
                                 {"seed", m.seed}}}};
  return args.dump();
}

namespace {

/// FNV-1a over everything the index shows: env_args, and each listed episode's name, flags and
/// size. Equal fingerprints mean an identical index.
std::string IndexFingerprint(const Session& session) {
  std::string text = EnvArgsJson(session.manifest());
  for (const auto* list : {&session.demos(), &session.play_chunks()}) {
    for (const EpisodeEntry& e : *list) {
      text += "|" + e.name + ":" + std::to_string(e.meta.num_samples) + ":" + e.flags.split +
              (e.flags.bad ? ":bad" : "") + (e.problem.empty() ? "" : ":damaged");
    }
  }
  return std::to_string(Fnv1a(text));
}

}  // namespace

bool SessionIndexIsCurrent(const Session& session, const std::string& path) {
  if (!fs::exists(path)) return false;
  try {
    const h5::File file = h5::File::OpenReadOnly(path);
    return h5::HasAttribute(file.id(), "recon_fingerprint") &&
           h5::ReadStringAttribute(file, file.id(), "recon_fingerprint") ==
               IndexFingerprint(session);
  } catch (const UserError&) {
    return false;  // unreadable: rebuild it
  }
}

void WriteSessionIndex(const Session& session, const std::string& path) {
  // Derived from the episode files (and rebuilt on open), so it needs no fsync.
  WriteFileVia(path, Durability::kRename, [&](const std::string& tmp) {
    h5::File file = h5::File::Create(tmp);
    h5::WriteAttribute(file, file.id(), "recon_fingerprint", IndexFingerprint(session));
    const h5::Handle data = h5::CreateGroup(file, file.id(), "data");
    int64_t total = 0;
    std::vector<std::string> train, valid;
    for (const EpisodeEntry& demo : session.demos()) {
      if (demo.flags.bad || !demo.problem.empty()) continue;
      const std::string target = (fs::path("episodes") / (demo.name + ".h5")).string();
      h5::CreateExternalLink(file, data.id(), demo.name, target, "/");
      total += demo.meta.num_samples;
      (demo.flags.split == "valid" ? valid : train).push_back(demo.name);
    }
    h5::WriteAttribute(file, data.id(), "total", total);
    h5::WriteAttribute(file, data.id(), "env_args", EnvArgsJson(session.manifest()));
    const h5::Handle mask = h5::CreateGroup(file, file.id(), "mask");
    h5::WriteStrings(file, mask.id(), "train", train);
    h5::WriteStrings(file, mask.id(), "valid", valid);
    const h5::Handle play = h5::CreateGroup(file, file.id(), "play");
    int64_t play_total = 0;
    for (const EpisodeEntry& chunk : session.play_chunks()) {
      if (!chunk.problem.empty()) continue;
      const std::string target = (fs::path("play") / (chunk.name + ".h5")).string();
      h5::CreateExternalLink(file, play.id(), chunk.name, target, "/");
      play_total += chunk.meta.num_samples;
    }
    h5::WriteAttribute(file, play.id(), "total", play_total);
    file.Close();
  });
}

}  // namespace recon::store
