#include "engine/store/episode_file.h"

#include <cmath>
#include <ctime>
#include <set>

#include "engine/core/error.h"
#include "engine/core/value_bounds.h"
#include "engine/store/h5.h"
#include "engine/worlds/physical_bounds.h"

namespace recon::store {

namespace {

using h5::ElementType;

// Checks that every sample has the session's shapes and finite values before anything is
// written, so a bad sample never becomes a committed episode.
void CheckSample(const std::vector<float>& values, size_t expected, size_t index, const char* field,
                 const std::string& path) {
  if (values.size() != expected) {
    throw UserError(path + ": sample " + std::to_string(index) + " field '" + field + "' has " +
                    std::to_string(values.size()) + " values, the session expects " +
                    std::to_string(expected));
  }
  for (float v : values) {
    if (!std::isfinite(v)) {
      throw UserError(path + ": sample " + std::to_string(index) + " field '" + field +
                      "' holds a non-finite value");
    }
  }
}

struct ImageGeometry {
  hsize_t c = 0, h = 0, w = 0;
};

ImageGeometry Geometry(const DataSpec& spec) {
  return {static_cast<hsize_t>(spec.y_shape[0]), static_cast<hsize_t>(spec.y_shape[1]),
          static_cast<hsize_t>(spec.y_shape[2])};
}

/// Rows of one field, concatenated: (N, dim).
template <typename Row>
std::vector<float> Stack(const std::vector<Row>& rows, std::vector<float> Row::*field) {
  std::vector<float> out;
  if (!rows.empty()) out.reserve(rows.size() * (rows[0].*field).size());
  for (const Row& row : rows) out.insert(out.end(), (row.*field).begin(), (row.*field).end());
  return out;
}

/// Writes y for all rows: images become HWC (robomimic's layout), uint8 or float32.
template <typename Row>
void WriteObservation(const h5::File& file, hid_t obs, const SessionManifest& layout,
                      const std::vector<Row>& rows) {
  const DataSpec& spec = layout.spec;
  const hsize_t n = rows.size();
  if (!spec.YIsImage()) {
    const std::vector<float> y = Stack(rows, &Row::y);
    h5::WriteArray(file, obs, kEnvironmentKey, ElementType::kFloat32,
                   {n, static_cast<hsize_t>(spec.y_shape[0])}, y.data());
    return;
  }
  const ImageGeometry g = Geometry(spec);
  const size_t plane = g.h * g.w;
  const size_t frame = plane * g.c;
  if (layout.y_encoding == "uint8") {
    std::vector<uint8_t> pixels(n * frame);
    for (size_t i = 0; i < n; ++i) {
      const float* chw = rows[i].y.data();
      uint8_t* hwc = pixels.data() + i * frame;
      for (size_t p = 0; p < plane; ++p) {
        for (size_t c = 0; c < g.c; ++c) {
          const float v = chw[c * plane + p];
          const float rounded = std::nearbyint(v);
          if (rounded < 0.0f || rounded > 255.0f || std::fabs(v - rounded) > 1e-3f) {
            throw UserError(file.path() + ": sample " + std::to_string(i) +
                            " field 'y' is not an 8-bit image (value " + std::to_string(v) +
                            "); the session stores images as uint8");
          }
          hwc[p * g.c + c] = static_cast<uint8_t>(rounded);
        }
      }
    }
    h5::WriteArray(file, obs, kCameraImageKey, ElementType::kUInt8, {n, g.h, g.w, g.c},
                   pixels.data());
    return;
  }
  std::vector<float> values(n * frame);
  for (size_t i = 0; i < n; ++i) {
    const float* chw = rows[i].y.data();
    float* hwc = values.data() + i * frame;
    for (size_t p = 0; p < plane; ++p) {
      for (size_t c = 0; c < g.c; ++c) hwc[p * g.c + c] = chw[c * plane + p];
    }
  }
  h5::WriteArray(file, obs, kCameraImageKey, ElementType::kFloat32, {n, g.h, g.w, g.c},
                 values.data());
}

template <typename Row>
void WriteBeacons(const h5::File& file, hid_t obs, const SessionManifest& layout,
                  const std::vector<Row>& rows) {
  size_t offset = 0;
  for (const BeaconSpec& beacon : layout.beacons) {
    std::vector<float> values;
    values.reserve(rows.size() * beacon.dim);
    for (const Row& row : rows) {
      values.insert(values.end(), row.b.begin() + offset, row.b.begin() + offset + beacon.dim);
    }
    h5::WriteArray(file, obs, BeaconKey(beacon.name), ElementType::kFloat32,
                   {rows.size(), static_cast<hsize_t>(beacon.dim)}, values.data());
    offset += beacon.dim;
  }
}

void WriteMeta(const h5::File& file, hid_t root, const EpisodeMeta& meta, int64_t num_samples) {
  h5::WriteAttribute(file, root, "num_samples", num_samples);
  h5::WriteAttribute(file, root, "recon_kind", meta.kind);
  h5::WriteAttribute(file, root, "recon_seed", static_cast<int64_t>(meta.seed));
  h5::WriteAttribute(file, root, "recon_source", meta.source);
  h5::WriteAttribute(file, root, "recon_recorded_at", meta.recorded_at);
  h5::WriteAttribute(file, root, "recon_teaching_seconds", meta.teaching_seconds);
  h5::WriteAttribute(file, root, "recon_succeeded", static_cast<int64_t>(meta.succeeded));
}

void CheckWithin(const std::vector<ValueRange>& ranges, const std::vector<float>& values,
                 size_t index, const char* field, const std::string& path) {
  const std::string problem = OutOfBounds(ranges, values, field);
  if (!problem.empty()) {
    throw UserError(path + ": sample " + std::to_string(index) + " " + problem +
                    "; no robot of this cell records that (a damaged or edited file?)");
  }
}

// The u of a demonstration's sample; play samples have none.
void CheckActions(const Sample& sample, const DataSpec& spec, const ValueBounds& bounds,
                  size_t index, const std::string& path) {
  CheckSample(sample.u, spec.u_dim, index, "u", path);
  CheckWithin(bounds.u, sample.u, index, "u", path);
}
void CheckActions(const PlaySample&, const DataSpec&, const ValueBounds&, size_t,
                  const std::string&) {}

/// Shapes, finiteness and the world's physical bounds of every row, before a file is written
/// and after one is read: a value no robot of the session's world records is refused either way.
template <typename Row>
void CheckRows(const std::vector<Row>& rows, const SessionManifest& layout,
               const std::string& path) {
  const DataSpec& spec = layout.spec;
  const ValueBounds bounds = worlds::PhysicalBounds(layout.world, spec);
  for (size_t i = 0; i < rows.size(); ++i) {
    CheckSample(rows[i].x, spec.x_dim, i, "x", path);
    CheckSample(rows[i].y, static_cast<size_t>(spec.YSize()), i, "y", path);
    CheckSample(rows[i].b, spec.b_dim, i, "b", path);
    CheckWithin(bounds.x, rows[i].x, i, "x", path);
    CheckWithin(bounds.y, rows[i].y, i, "y", path);
    CheckWithin(bounds.b, rows[i].b, i, "b", path);
    CheckActions(rows[i], spec, bounds, i, path);
  }
}

void CheckShape(const h5::File& file, hid_t location, const std::string& name,
                const std::vector<hsize_t>& expected) {
  const std::vector<hsize_t> dims = h5::Dimensions(file, location, name);
  if (dims != expected) {
    h5::Fail(file.path(), "dataset '" + name + "' has shape " + h5::ShapeText(dims) +
                              ", the session expects " + h5::ShapeText(expected));
  }
}

/// Reads an (N, cols) float dataset and checks its shape.
std::vector<float> ReadMatrix(const h5::File& file, hid_t location, const std::string& name,
                              hsize_t rows, hsize_t cols) {
  CheckShape(file, location, name, {rows, cols});
  return h5::ReadFloats(file, location, name);
}

/// Reads y of every row (HWC on disk, CHW in memory) into rows[i].y.
template <typename Row>
void ReadObservation(const h5::File& file, hid_t obs, const SessionManifest& layout,
                     std::vector<Row>& rows) {
  const DataSpec& spec = layout.spec;
  const hsize_t n = rows.size();
  if (!spec.YIsImage()) {
    const hsize_t m = static_cast<hsize_t>(spec.y_shape[0]);
    const std::vector<float> y = ReadMatrix(file, obs, std::string("obs/") + kEnvironmentKey, n, m);
    for (size_t i = 0; i < n; ++i) rows[i].y.assign(y.begin() + i * m, y.begin() + (i + 1) * m);
    return;
  }
  const ImageGeometry g = Geometry(spec);
  const std::string name = std::string("obs/") + kCameraImageKey;
  CheckShape(file, obs, name, {n, g.h, g.w, g.c});
  const size_t plane = g.h * g.w;
  const size_t frame = plane * g.c;
  auto convert = [&](const auto& hwc_all) {
    for (size_t i = 0; i < n; ++i) {
      std::vector<float>& chw = rows[i].y;
      chw.resize(frame);
      const auto* hwc = hwc_all.data() + i * frame;
      for (size_t p = 0; p < plane; ++p) {
        for (size_t c = 0; c < g.c; ++c) chw[c * plane + p] = static_cast<float>(hwc[p * g.c + c]);
      }
    }
  };
  if (h5::IsUInt8(file, obs, name)) {
    convert(h5::ReadBytes(file, obs, name));
  } else {
    convert(h5::ReadFloats(file, obs, name));
  }
}

template <typename Row>
void ReadBeacons(const h5::File& file, hid_t root, const SessionManifest& layout,
                 std::vector<Row>& rows) {
  for (Row& row : rows) row.b.clear();
  for (const BeaconSpec& beacon : layout.beacons) {
    const std::vector<float> values = ReadMatrix(file, root, "obs/" + BeaconKey(beacon.name),
                                                 rows.size(), static_cast<hsize_t>(beacon.dim));
    for (size_t i = 0; i < rows.size(); ++i) {
      rows[i].b.insert(rows[i].b.end(), values.begin() + i * beacon.dim,
                       values.begin() + (i + 1) * beacon.dim);
    }
  }
}

template <typename Row>
void ReadStateAndObservations(const h5::File& file, hid_t root, const SessionManifest& layout,
                              std::vector<Row>& rows) {
  const hsize_t n = rows.size();
  const hsize_t x_dim = static_cast<hsize_t>(layout.spec.x_dim);
  const std::vector<float> x =
      ReadMatrix(file, root, std::string("obs/") + kRobotStateKey, n, x_dim);
  for (size_t i = 0; i < n; ++i) {
    rows[i].x.assign(x.begin() + i * x_dim, x.begin() + (i + 1) * x_dim);
  }
  ReadObservation(file, root, layout, rows);
  ReadBeacons(file, root, layout, rows);
}

// The datasets ReadStateAndObservations reads, relative to the episode's group.
std::set<std::string> StateAndObservationNames(const SessionManifest& layout) {
  std::set<std::string> names = {std::string("obs/") + kRobotStateKey,
                                 "obs/" + ObservationKey(layout)};
  for (const BeaconSpec& beacon : layout.beacons) names.insert("obs/" + BeaconKey(beacon.name));
  return names;
}

template <typename Row>
void WriteStateAndObservations(const h5::File& file, hid_t root, const SessionManifest& layout,
                               const std::vector<Row>& rows, const char* group = "obs") {
  const h5::Handle obs = h5::CreateGroup(file, root, group);
  const std::vector<float> x = Stack(rows, &Row::x);
  h5::WriteArray(file, obs.id(), kRobotStateKey, ElementType::kFloat32,
                 {rows.size(), static_cast<hsize_t>(layout.spec.x_dim)}, x.data());
  WriteObservation(file, obs.id(), layout, rows);
  WriteBeacons(file, obs.id(), layout, rows);
}

}  // namespace

std::string BeaconKey(const std::string& beacon_name) { return "beacon_" + beacon_name; }

std::string ObservationKey(const SessionManifest& layout) {
  return layout.spec.YIsImage() ? kCameraImageKey : kEnvironmentKey;
}

void WriteDemoGroup(const h5::File& file, hid_t group, const SessionManifest& layout,
                    const DemoRecord& record, bool next_obs) {
  const std::vector<Sample>& samples = record.episode.samples;
  const std::string& path = file.path();
  if (samples.empty()) throw UserError(path + ": a demonstration needs at least one sample");
  CheckRows(samples, layout, path);
  if (!record.rewards.empty() && record.rewards.size() != samples.size()) {
    throw UserError(path + ": " + std::to_string(record.rewards.size()) + " rewards for " +
                    std::to_string(samples.size()) + " samples");
  }
  const hsize_t n = samples.size();
  WriteMeta(file, group, record.meta, static_cast<int64_t>(n));
  WriteStateAndObservations(file, group, layout, samples);
  if (next_obs) {
    // robomimic's next_obs: the observation after each step; the last repeats (the episode ends).
    std::vector<Sample> next(samples.begin() + 1, samples.end());
    next.push_back(samples.back());
    WriteStateAndObservations(file, group, layout, next, "next_obs");
  }
  const std::vector<float> u = Stack(samples, &Sample::u);
  h5::WriteArray(file, group, "actions", ElementType::kFloat32,
                 {n, static_cast<hsize_t>(layout.spec.u_dim)}, u.data());
  std::vector<double> rewards = record.rewards;
  rewards.resize(n, 0.0);
  h5::WriteArray(file, group, "rewards", ElementType::kFloat64, {n}, rewards.data());
  std::vector<int64_t> dones(n, 0);
  dones.back() = 1;
  h5::WriteArray(file, group, "dones", ElementType::kInt64, {n}, dones.data());
  const std::vector<float> x = Stack(samples, &Sample::x);
  h5::WriteArray(file, group, "states", ElementType::kFloat32,
                 {n, static_cast<hsize_t>(layout.spec.x_dim)}, x.data());
}

void WritePlayGroup(const h5::File& file, hid_t group, const SessionManifest& layout,
                    const PlayRecord& record) {
  if (record.samples.empty()) {
    throw UserError(file.path() + ": a play chunk needs at least one sample");
  }
  CheckRows(record.samples, layout, file.path());
  WriteMeta(file, group, record.meta, static_cast<int64_t>(record.samples.size()));
  WriteStateAndObservations(file, group, layout, record.samples);
}

void WriteDemoFile(const std::string& path, const SessionManifest& layout,
                   const DemoRecord& record) {
  h5::File file = h5::File::Create(path);
  WriteDemoGroup(file, file.id(), layout, record, false);
  file.Close();
}

void WritePlayFile(const std::string& path, const SessionManifest& layout,
                   const PlayRecord& record) {
  h5::File file = h5::File::Create(path);
  WritePlayGroup(file, file.id(), layout, record);
  file.Close();
}

EpisodeMeta ReadEpisodeMeta(const h5::File& file, hid_t root) {
  const std::string& path = file.path();
  EpisodeMeta meta;
  meta.num_samples = h5::ReadIntAttribute(file, root, "num_samples");
  if (meta.num_samples <= 0) h5::Fail(path, "attribute 'num_samples' must be positive");
  meta.kind = h5::ReadStringAttribute(file, root, "recon_kind");
  if (meta.kind != "demo" && meta.kind != "play") {
    h5::Fail(path,
             "attribute 'recon_kind' must be \"demo\" or \"play\" (got \"" + meta.kind + "\")");
  }
  meta.seed = static_cast<uint64_t>(h5::ReadIntAttribute(file, root, "recon_seed"));
  meta.source = h5::ReadStringAttribute(file, root, "recon_source");
  meta.recorded_at = h5::ReadStringAttribute(file, root, "recon_recorded_at");
  meta.teaching_seconds = h5::ReadDoubleAttribute(file, root, "recon_teaching_seconds");
  meta.succeeded = h5::ReadIntAttribute(file, root, "recon_succeeded") != 0;
  return meta;
}

EpisodeMeta ReadEpisodeMeta(const std::string& path) {
  const h5::File file = h5::File::OpenReadOnly(path);
  return ReadEpisodeMeta(file, file.id());
}

void CheckEpisodeShapes(const std::string& path, const SessionManifest& layout,
                        const EpisodeMeta& meta) {
  const h5::File file = h5::File::OpenReadOnly(path);
  const hsize_t n = static_cast<hsize_t>(meta.num_samples);
  const DataSpec& spec = layout.spec;
  const hid_t root = file.id();
  CheckShape(file, root, std::string("obs/") + kRobotStateKey,
             {n, static_cast<hsize_t>(spec.x_dim)});
  if (spec.YIsImage()) {
    const ImageGeometry g = Geometry(spec);
    CheckShape(file, root, std::string("obs/") + kCameraImageKey, {n, g.h, g.w, g.c});
  } else {
    CheckShape(file, root, std::string("obs/") + kEnvironmentKey,
               {n, static_cast<hsize_t>(spec.y_shape[0])});
  }
  for (const BeaconSpec& beacon : layout.beacons) {
    CheckShape(file, root, "obs/" + BeaconKey(beacon.name), {n, static_cast<hsize_t>(beacon.dim)});
  }
  if (meta.kind == "demo") {
    CheckShape(file, root, "actions", {n, static_cast<hsize_t>(spec.u_dim)});
    CheckShape(file, root, "rewards", {n});
  }
}

DemoRecord ReadDemoGroup(const h5::File& file, hid_t group, const SessionManifest& layout) {
  DemoRecord record;
  record.meta = ReadEpisodeMeta(file, group);
  if (record.meta.kind != "demo") h5::Fail(file.path(), "holds play data, not a demonstration");
  const hsize_t n = static_cast<hsize_t>(record.meta.num_samples);
  std::vector<Sample>& samples = record.episode.samples;
  samples.resize(n);
  ReadStateAndObservations(file, group, layout, samples);
  const hsize_t u_dim = static_cast<hsize_t>(layout.spec.u_dim);
  const std::vector<float> u = ReadMatrix(file, group, "actions", n, u_dim);
  for (size_t i = 0; i < n; ++i) {
    samples[i].u.assign(u.begin() + i * u_dim, u.begin() + (i + 1) * u_dim);
  }
  CheckShape(file, group, "rewards", {n});
  const std::vector<float> rewards = h5::ReadFloats(file, group, "rewards");
  record.rewards.assign(rewards.begin(), rewards.end());
  std::set<std::string> read = StateAndObservationNames(layout);
  read.insert({"actions", "rewards"});
  h5::VerifyChecksums(file, group, read);  // what nothing above reads: states, dones, next_obs
  CheckRows(samples, layout, file.path());
  return record;
}

PlayRecord ReadPlayGroup(const h5::File& file, hid_t group, const SessionManifest& layout) {
  PlayRecord record;
  record.meta = ReadEpisodeMeta(file, group);
  if (record.meta.kind != "play") h5::Fail(file.path(), "holds a demonstration, not play data");
  record.samples.resize(static_cast<size_t>(record.meta.num_samples));
  ReadStateAndObservations(file, group, layout, record.samples);
  h5::VerifyChecksums(file, group, StateAndObservationNames(layout));  // anything else in it
  CheckRows(record.samples, layout, file.path());
  return record;
}

DemoRecord ReadDemoFile(const std::string& path, const SessionManifest& layout) {
  const h5::File file = h5::File::OpenReadOnly(path);
  return ReadDemoGroup(file, file.id(), layout);
}

PlayRecord ReadPlayFile(const std::string& path, const SessionManifest& layout) {
  const h5::File file = h5::File::OpenReadOnly(path);
  return ReadPlayGroup(file, file.id(), layout);
}

std::string NowIso8601() {
  char text[32];
  const std::time_t now = std::time(nullptr);
  std::tm utc;
  gmtime_r(&now, &utc);
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace recon::store
