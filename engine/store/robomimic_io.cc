#include "engine/store/robomimic_io.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/store/atomic_file.h"
#include "engine/store/h5.h"
#include "engine/store/session_index.h"

namespace recon::store {

namespace fs = std::filesystem;

namespace {

// A session being imported is built in "<target>.importing.<pid>" and renamed into place.
constexpr char kStagingMarker[] = ".importing.";

/// <prefix>N names of a group in number order (robomimic sorts demo_N the same way).
std::vector<std::string> NumberedNames(const h5::File& file, hid_t group,
                                       const std::string& prefix = "demo_") {
  std::vector<std::pair<long, std::string>> numbered;
  for (const std::string& name : h5::ListChildren(file, group)) {
    if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size()) continue;
    const std::string digits = name.substr(prefix.size());
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(c); })) {
      continue;
    }
    numbered.emplace_back(std::stol(digits), name);
  }
  std::sort(numbered.begin(), numbered.end());
  std::vector<std::string> names;
  for (auto& [number, name] : numbered) names.push_back(name);
  return names;
}

/// A beacon name from an obs key: "beacon_plate" -> "plate", "object-pos" -> "object_pos".
std::string BeaconNameFromKey(const std::string& key) {
  std::string name = key.rfind("beacon_", 0) == 0 ? key.substr(7) : key;
  for (char& c : name) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name.empty() ? "beacon" : name;
}

/// Width of one row of an obs key: (N, d) -> d, (N,) -> 1.
hsize_t RowWidth(const h5::File& file, hid_t demo, const std::string& key,
                 const std::string& where) {
  const std::vector<hsize_t> dims = h5::Dimensions(file, demo, "obs/" + key);
  if (dims.size() == 1) return 1;
  if (dims.size() == 2) return dims[1];
  h5::Fail(file.path(), where + ": obs key '" + key + "' has shape " + h5::ShapeText(dims) +
                            "; robot state and beacon keys must be vectors per sample");
}

/// Builds the manifest of a session imported from a file RECON Studio did not write.
SessionManifest ManifestFromMapping(const h5::File& file, hid_t data, const std::string& first,
                                    const ImportMapping& mapping) {
  const h5::Handle demo = h5::OpenGroup(file, data, first);
  const std::string where = "data/" + first;
  SessionManifest m;
  m.created_at = NowIso8601();
  m.created_by = "recon 0.1.0";
  m.world = "imported";
  m.cell = "imported";
  m.placement = mapping.beacon_keys.empty() ? "none" : "imported";
  m.devices = {{"source", "robomimic-file", fs::absolute(file.path()).string()}};
  for (const std::string& key : mapping.x_keys) {
    m.spec.x_dim += static_cast<int>(RowWidth(file, demo.id(), key, where));
  }
  const std::vector<hsize_t> y_dims = h5::Dimensions(file, demo.id(), "obs/" + mapping.y_key);
  if (y_dims.size() == 4) {
    m.spec.y_shape = {static_cast<int64_t>(y_dims[3]), static_cast<int64_t>(y_dims[1]),
                      static_cast<int64_t>(y_dims[2])};
    m.y_encoding = h5::IsUInt8(file, demo.id(), "obs/" + mapping.y_key) ? "uint8" : "float32";
  } else if (y_dims.size() == 2) {
    m.spec.y_shape = {static_cast<int64_t>(y_dims[1])};
  } else {
    h5::Fail(file.path(), where + ": obs key '" + mapping.y_key + "' has shape " +
                              h5::ShapeText(y_dims) +
                              "; y must be images (N, H, W, C) or vectors (N, m)");
  }
  for (const std::string& key : mapping.beacon_keys) {
    BeaconSpec beacon;
    beacon.name = BeaconNameFromKey(key);
    beacon.object = "obs key " + key;
    beacon.quantity = "imported";
    beacon.dim = static_cast<int>(RowWidth(file, demo.id(), key, where));
    m.beacons.push_back(beacon);
  }
  m.spec.b_dim = TotalBeaconDim(m.beacons);
  const std::vector<hsize_t> u_dims = h5::Dimensions(file, demo.id(), "actions");
  if (u_dims.size() != 2) {
    h5::Fail(file.path(), where + ": dataset 'actions' has shape " + h5::ShapeText(u_dims) +
                              "; expected (N, action size)");
  }
  m.spec.u_dim = static_cast<int>(u_dims[1]);
  return m;
}

/// Reads one demonstration of a foreign robomimic file through the mapping.
DemoRecord ReadMappedDemo(const h5::File& file, hid_t data, const std::string& name,
                          const SessionManifest& layout, const ImportMapping& mapping) {
  const h5::Handle demo = h5::OpenGroup(file, data, name);
  const std::string where = "data/" + name;
  const std::vector<hsize_t> u_dims = h5::Dimensions(file, demo.id(), "actions");
  if (u_dims.size() != 2 || u_dims[1] != static_cast<hsize_t>(layout.spec.u_dim)) {
    h5::Fail(file.path(), where + ": dataset 'actions' has shape " + h5::ShapeText(u_dims) +
                              ", the first demonstration's actions have " +
                              std::to_string(layout.spec.u_dim) + " values");
  }
  const size_t n = u_dims[0];
  if (n == 0) h5::Fail(file.path(), where + " has no samples");
  DemoRecord record;
  record.meta.kind = "demo";
  record.meta.num_samples = static_cast<int64_t>(n);
  record.meta.source = "import:" + fs::path(file.path()).filename().string();
  record.meta.recorded_at = NowIso8601();
  std::vector<Sample>& samples = record.episode.samples;
  samples.resize(n);
  // Appends the rows of `key` to each sample's `field`, checking the row count and width.
  const auto append = [&](const std::string& key, std::vector<float> Sample::*field,
                          hsize_t expected_width) {
    const std::vector<hsize_t> dims = h5::Dimensions(file, demo.id(), "obs/" + key);
    const hsize_t width = dims.size() == 2 ? dims[1] : 1;
    if (dims.empty() || dims[0] != n || dims.size() > 2 || width != expected_width) {
      h5::Fail(file.path(), where + ": obs key '" + key + "' has shape " + h5::ShapeText(dims) +
                                ", expected (" + std::to_string(n) + ", " +
                                std::to_string(expected_width) + ")");
    }
    const std::vector<float> values = h5::ReadFloats(file, demo.id(), "obs/" + key);
    for (size_t i = 0; i < n; ++i) {
      (samples[i].*field)
          .insert((samples[i].*field).end(), values.begin() + i * width,
                  values.begin() + (i + 1) * width);
    }
  };
  const h5::Handle first_demo = h5::OpenGroup(file, data, name);
  for (const std::string& key : mapping.x_keys) {
    append(key, &Sample::x, RowWidth(file, first_demo.id(), key, where));
  }
  if (layout.spec.YIsImage()) {
    const hsize_t c = layout.spec.y_shape[0], h = layout.spec.y_shape[1],
                  w = layout.spec.y_shape[2];
    const std::string key = "obs/" + mapping.y_key;
    const std::vector<hsize_t> dims = h5::Dimensions(file, demo.id(), key);
    if (dims != std::vector<hsize_t>{n, h, w, c}) {
      h5::Fail(file.path(), where + ": obs key '" + mapping.y_key + "' has shape " +
                                h5::ShapeText(dims) + ", expected " + h5::ShapeText({n, h, w, c}));
    }
    const std::vector<float> hwc = h5::ReadFloats(file, demo.id(), key);
    const size_t plane = h * w;
    for (size_t i = 0; i < n; ++i) {
      samples[i].y.resize(plane * c);
      const float* src = hwc.data() + i * plane * c;
      for (size_t p = 0; p < plane; ++p) {
        for (size_t k = 0; k < c; ++k) samples[i].y[k * plane + p] = src[p * c + k];
      }
    }
  } else {
    append(mapping.y_key, &Sample::y, static_cast<hsize_t>(layout.spec.y_shape[0]));
  }
  for (size_t k = 0; k < mapping.beacon_keys.size(); ++k) {
    append(mapping.beacon_keys[k], &Sample::b, static_cast<hsize_t>(layout.beacons[k].dim));
  }
  const std::vector<float> u = h5::ReadFloats(file, demo.id(), "actions");
  const size_t u_dim = layout.spec.u_dim;
  for (size_t i = 0; i < n; ++i) {
    samples[i].u.assign(u.begin() + i * u_dim, u.begin() + (i + 1) * u_dim);
  }
  if (h5::Exists(demo.id(), "rewards")) {
    const std::vector<float> rewards = h5::ReadFloats(file, demo.id(), "rewards");
    if (rewards.size() == n) record.rewards.assign(rewards.begin(), rewards.end());
  }
  record.meta.succeeded = !record.rewards.empty() && record.rewards.back() > 0.5;
  return record;
}

std::vector<std::string> ValidNames(const h5::File& file) {
  if (!h5::Exists(file.id(), "mask/valid")) return {};
  return h5::ReadStrings(file, file.id(), "mask/valid");
}

}  // namespace

ExportSummary ExportRobomimic(const Session& session, const std::string& path,
                              const ExportOptions& options) {
  const SessionManifest& manifest = session.manifest();
  ExportSummary summary;
  WriteFileVia(path, Durability::kFsync, [&](const std::string& tmp) {
    h5::File file = h5::File::Create(tmp);
    h5::WriteAttribute(file, file.id(), "recon_manifest", ManifestToJson(manifest));
    const h5::Handle data = h5::CreateGroup(file, file.id(), "data");
    std::vector<std::string> train, valid;
    for (const EpisodeEntry& demo : session.demos()) {
      if (demo.flags.bad && !options.include_bad) continue;
      if (!demo.problem.empty()) throw UserError(demo.problem);
      const DemoRecord record = session.ReadDemo(demo.name);
      const h5::Handle group = h5::CreateGroup(file, data.id(), demo.name);
      WriteDemoGroup(file, group.id(), manifest, record, options.next_obs);
      (demo.flags.split == "valid" ? valid : train).push_back(demo.name);
      ++summary.demos;
      summary.samples += demo.meta.num_samples;
    }
    h5::WriteAttribute(file, data.id(), "total", summary.samples);
    h5::WriteAttribute(file, data.id(), "env_args", EnvArgsJson(manifest));
    const h5::Handle mask = h5::CreateGroup(file, file.id(), "mask");
    h5::WriteStrings(file, mask.id(), "train", train);
    h5::WriteStrings(file, mask.id(), "valid", valid);
    if (options.include_play) {
      const h5::Handle play = h5::CreateGroup(file, file.id(), "play");
      for (const EpisodeEntry& chunk : session.play_chunks()) {
        if (!chunk.problem.empty()) throw UserError(chunk.problem);
        const h5::Handle group = h5::CreateGroup(file, play.id(), chunk.name);
        WritePlayGroup(file, group.id(), manifest, session.ReadPlay(chunk.name));
        ++summary.play_chunks;
        summary.play_samples += chunk.meta.num_samples;
      }
      h5::WriteAttribute(file, play.id(), "total", summary.play_samples);
    }
    file.Close();
  });
  return summary;
}

std::vector<std::string> DescribeObsKeys(const std::string& path) {
  const h5::File file = h5::File::OpenReadOnly(path);
  const h5::Handle data = h5::OpenGroup(file, file.id(), "data");
  const std::vector<std::string> demos = NumberedNames(file, data.id());
  if (demos.empty()) h5::Fail(path, "group 'data' holds no demo_N groups");
  const h5::Handle obs = h5::OpenGroup(file, data.id(), demos.front() + "/obs");
  std::vector<std::string> keys;
  for (const std::string& key : h5::ListChildren(file, obs.id())) {
    const bool bytes = h5::IsUInt8(file, obs.id(), key);
    keys.push_back(key + " " + h5::ShapeText(h5::Dimensions(file, obs.id(), key)) +
                   (bytes ? " uint8" : ""));
  }
  return keys;
}

ImportSummary ImportRobomimic(const std::string& path, const std::string& session_dir,
                              const ImportMapping& mapping) {
  if (Session::Exists(session_dir)) {
    throw UserError(session_dir + " already holds a teaching session; import into a new folder");
  }
  if (fs::exists(session_dir) && !(fs::is_directory(session_dir) && fs::is_empty(session_dir))) {
    throw UserError(session_dir + " already exists; import into a new (or empty) folder");
  }
  const h5::File file = h5::File::OpenReadOnly(path);
  if (!h5::Exists(file.id(), "data")) {
    h5::Fail(path, "not a robomimic file: it has no group 'data'");
  }
  const h5::Handle data = h5::OpenGroup(file, file.id(), "data");
  const std::vector<std::string> names = NumberedNames(file, data.id());
  if (names.empty()) h5::Fail(path, "group 'data' holds no demo_N groups");

  ImportSummary summary;
  summary.from_recon = h5::HasAttribute(file.id(), "recon_manifest");
  SessionManifest manifest;
  std::map<std::string, EpisodeFlags> source_flags;  // by the file's demo names
  if (summary.from_recon) {
    manifest = ManifestFromJson(h5::ReadStringAttribute(file, file.id(), "recon_manifest"),
                                path + " (attribute recon_manifest)");
    source_flags = std::move(manifest.episode_flags);
    manifest.episode_flags.clear();
  } else {
    if (mapping.x_keys.empty() || mapping.y_key.empty()) {
      throw UserError(path +
                      " was not written by RECON Studio: say which obs keys are the robot "
                      "state (--x-keys a,b), the observation (--y-key) and the beacons "
                      "(--beacon-keys); its keys are: " +
                      JoinNames(DescribeObsKeys(path)));
    }
    manifest = ManifestFromMapping(file, data.id(), names.front(), mapping);
  }

  // Built in a sibling folder and renamed into place at the end: a file that fails half-way
  // leaves no half-imported session.
  const fs::path target = fs::path(session_dir);
  const std::string staging = session_dir + kStagingMarker + std::to_string(getpid());
  std::error_code ignored;
  fs::remove_all(staging, ignored);
  // What an import killed half-way (kill -9, a power cut) left beside the target.
  RemoveDeadStagingFoldersOf(session_dir, kStagingMarker);
  try {
    {
      Session session = Session::Create(staging, manifest);
      session.DeferIndex(true);
      const std::vector<std::string> valid = ValidNames(file);
      for (const std::string& name : names) {
        DemoRecord record;
        if (summary.from_recon) {
          const h5::Handle group = h5::OpenGroup(file, data.id(), name);
          record = ReadDemoGroup(file, group.id(), manifest);
        } else {
          record = ReadMappedDemo(file, data.id(), name, manifest, mapping);
        }
        const EpisodeEntry& entry = session.CommitDemo(record);
        // Demonstrations are renumbered from demo_0 in order; their flags follow them.
        EpisodeFlags flags;
        if (auto it = source_flags.find(name); it != source_flags.end()) flags = it->second;
        if (std::find(valid.begin(), valid.end(), name) != valid.end()) flags.split = "valid";
        if (!(flags == EpisodeFlags{})) session.SetFlags(entry.name, flags);
        ++summary.demos;
        summary.samples += entry.meta.num_samples;
      }
      if (summary.from_recon && h5::Exists(file.id(), "play")) {
        const h5::Handle play = h5::OpenGroup(file, file.id(), "play");
        for (const std::string& name : NumberedNames(file, play.id(), "play_")) {
          const h5::Handle group = h5::OpenGroup(file, play.id(), name);
          const EpisodeEntry& entry = session.CommitPlay(ReadPlayGroup(file, group.id(), manifest));
          summary.play_samples += entry.meta.num_samples;
        }
      }
      session.DeferIndex(false);
    }
    if (target.has_parent_path()) fs::create_directories(target.parent_path());
    std::error_code renamed;
    fs::rename(staging, target, renamed);
    if (renamed) throw UserError("cannot write " + staging + ": " + renamed.message());
  } catch (const UserError& e) {
    fs::remove_all(staging, ignored);
    // The user asked for the session folder, not the staging folder it was built in.
    throw UserError(NameTheTarget(e.what(), staging, session_dir));
  } catch (...) {
    fs::remove_all(staging, ignored);
    throw;
  }
  return summary;
}

}  // namespace recon::store
