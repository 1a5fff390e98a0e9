#include "engine/store/manifest.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/store/json_fields.h"

namespace recon::store {

namespace {

using json = nlohmann::json;

json SpecToJson(const DataSpec& spec) {
  return {{"x_dim", spec.x_dim},
          {"y_shape", spec.y_shape},
          {"b_dim", spec.b_dim},
          {"u_dim", spec.u_dim}};
}

DataSpec SpecFromJson(const FieldReader& reader) {
  DataSpec spec;
  spec.x_dim = static_cast<int>(reader.NonNegativeInteger("x_dim"));
  spec.b_dim = static_cast<int>(reader.NonNegativeInteger("b_dim"));
  spec.u_dim = static_cast<int>(reader.NonNegativeInteger("u_dim"));
  const json& shape = reader.Array("y_shape");
  if (shape.size() != 1 && shape.size() != 3) {
    reader.Fail(reader.Name("y_shape"), "must have 1 (vector) or 3 (C, H, W) entries");
  }
  for (const json& d : shape) {
    if (!d.is_number_integer() || d.get<int64_t>() <= 0) {
      reader.Fail(reader.Name("y_shape"), "must hold positive integers");
    }
    spec.y_shape.push_back(d.get<int64_t>());
  }
  return spec;
}

}  // namespace

std::string ManifestToJson(const SessionManifest& m) {
  json devices = json::array();
  for (const DeviceEntry& d : m.devices) {
    devices.push_back({{"role", d.role}, {"kind", d.kind}, {"detail", d.detail}});
  }
  json beacons = json::array();
  for (const BeaconSpec& b : m.beacons) {
    beacons.push_back({{"name", b.name},
                       {"object", b.object},
                       {"quantity", b.quantity},
                       {"dim", b.dim},
                       {"unit", b.unit}});
  }
  json flags = json::object();
  for (const auto& [name, f] : m.episode_flags) {
    flags[name] = {{"bad", f.bad}, {"split", f.split}, {"note", f.note}};
  }
  const json root = {{"format", "recon-session"},
                     {"version", m.version},
                     {"created_at", m.created_at},
                     {"created_by", m.created_by},
                     {"cell",
                      {{"world", m.world},
                       {"kind", m.cell},
                       {"placement", m.placement},
                       {"layout", m.layout},
                       {"beacon_noise_sigma", m.beacon_noise_sigma},
                       {"demo_noise_sigma", m.demo_noise_sigma},
                       {"image_size", m.image_size},
                       {"step_seconds", m.step_seconds},
                       {"devices", devices}}},
                     {"beacons", beacons},
                     {"spec", SpecToJson(m.spec)},
                     {"y_encoding", m.y_encoding},
                     {"calibration_file", m.calibration_file},
                     {"seeds", {{"session", m.seed}}},
                     {"ledger",
                      {{"seconds_per_beacon_placement", m.seconds_per_beacon_placement},
                       {"placements_per_beacon", m.placements_per_beacon},
                       {"discarded_takes", m.discarded_takes},
                       {"discarded_seconds", m.discarded_seconds},
                       {"countdown_seconds", m.countdown_seconds},
                       {"teleop", m.teleop}}},
                     {"episodes", flags},
                     {"beacon_assignments", m.beacon_assignments}};
  return root.dump(2) + "\n";
}

SessionManifest ManifestFromJson(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw UserError(source + ": not valid JSON (" + e.what() + ")");
  }
  const FieldReader top(root, source, "");
  if (top.String("format") != "recon-session") {
    top.Fail("format", "must be \"recon-session\" (this is not a RECON Studio session manifest)");
  }
  SessionManifest m;
  m.version = static_cast<int>(top.Integer("version"));
  if (m.version > kManifestVersion) {
    throw UserError(source + ": field 'version' is " + std::to_string(m.version) +
                    ", written by a newer RECON Studio; this one reads versions up to " +
                    std::to_string(kManifestVersion) + ". Update RECON Studio to open it.");
  }
  if (m.version < 1) top.Fail("version", "must be at least 1");
  m.created_at = top.String("created_at");
  m.created_by = top.String("created_by");

  const FieldReader cell = top.Object("cell");
  m.world = cell.String("world");
  m.cell = cell.String("kind");
  m.placement = cell.String("placement");
  // Tabletop sessions written before layouts existed were recorded in what is now "wide".
  m.layout = cell.OptionalString("layout", m.world == "tabletop" ? "wide" : "");
  m.beacon_noise_sigma = cell.Number("beacon_noise_sigma");
  m.demo_noise_sigma = cell.OptionalNumber("demo_noise_sigma", 0.0);
  if (!std::isfinite(m.demo_noise_sigma) || m.demo_noise_sigma < 0) {
    cell.Fail(cell.Name("demo_noise_sigma"), "must be a non-negative number");
  }
  m.image_size = static_cast<int>(cell.NonNegativeInteger("image_size"));
  m.step_seconds = cell.Number("step_seconds");
  const json& devices = cell.Array("devices");
  for (size_t i = 0; i < devices.size(); ++i) {
    const FieldReader d = cell.Element(devices[i], "devices", i);
    m.devices.push_back({d.String("role"), d.String("kind"), d.OptionalString("detail", "")});
  }

  const json& beacons = top.Array("beacons");
  for (size_t i = 0; i < beacons.size(); ++i) {
    const FieldReader b = top.Element(beacons[i], "beacons", i);
    BeaconSpec beacon;
    beacon.name = b.String("name");
    beacon.object = b.String("object");
    beacon.quantity = b.String("quantity");
    beacon.dim = static_cast<int>(b.Integer("dim"));
    if (beacon.dim <= 0) b.Fail(b.Name("dim"), "must be positive");
    beacon.unit = b.OptionalString("unit", "");
    if (beacon.name.empty() || beacon.name.find_first_not_of(
                                   "abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos) {
      b.Fail(b.Name("name"),
             "must be lower-case letters, digits and '_' (got '" + beacon.name + "')");
    }
    m.beacons.push_back(beacon);
  }
  m.spec = SpecFromJson(top.Object("spec"));
  if (TotalBeaconDim(m.beacons) != m.spec.b_dim) {
    top.Fail("beacons", "add up to " + std::to_string(TotalBeaconDim(m.beacons)) +
                            " numbers but spec.b_dim is " + std::to_string(m.spec.b_dim));
  }
  m.y_encoding = top.String("y_encoding");
  if (m.y_encoding != "uint8" && m.y_encoding != "float32") {
    top.Fail("y_encoding", "must be \"uint8\" or \"float32\" (got \"" + m.y_encoding + "\")");
  }
  if (m.y_encoding == "uint8" && !m.spec.YIsImage()) {
    top.Fail("y_encoding", "is \"uint8\" but spec.y_shape is not an image");
  }
  m.calibration_file = top.String("calibration_file");
  m.seed = top.Object("seeds").Unsigned("session");
  const FieldReader ledger = top.Object("ledger");
  m.seconds_per_beacon_placement = ledger.Number("seconds_per_beacon_placement");
  m.placements_per_beacon = static_cast<int>(ledger.NonNegativeInteger("placements_per_beacon"));
  // Optional: sessions from before the ledger counted what was not kept lack them.
  if (ledger.Has("discarded_takes")) {
    m.discarded_takes = static_cast<int>(ledger.NonNegativeInteger("discarded_takes"));
  }
  // Each read once, then checked: seconds, never negative.
  const auto seconds = [&](const char* field) {
    const double v = ledger.OptionalNumber(field, 0.0);
    if (!(v >= 0) || !std::isfinite(v)) {
      ledger.Fail(ledger.Name(field), "must be a number of seconds >= 0");
    }
    return v;
  };
  m.discarded_seconds = seconds("discarded_seconds");
  m.countdown_seconds = seconds("countdown_seconds");
  m.teleop = ledger.OptionalString("teleop", "");
  if (!m.teleop.empty() && m.teleop != "scripted" && m.teleop != "keyboard" &&
      m.teleop != "gamepad") {
    ledger.Fail(ledger.Name("teleop"),
                "must be \"scripted\", \"keyboard\" or \"gamepad\" (got \"" + m.teleop + "\")");
  }

  if (root.contains("beacon_assignments")) {  // optional: sessions from before the studio lack it
    const FieldReader assignments = top.Object("beacon_assignments");
    for (const auto& [beacon, object] : assignments.object().items()) {
      const bool known = std::any_of(m.beacons.begin(), m.beacons.end(),
                                     [&](const BeaconSpec& b) { return b.name == beacon; });
      if (!known) assignments.Fail(assignments.Name(beacon), "names no beacon of this session");
      m.beacon_assignments[beacon] = assignments.String(beacon);
    }
  }
  const FieldReader episodes = top.Object("episodes");
  for (const auto& [name, value] : episodes.object().items()) {
    const FieldReader f = episodes.Object(name);
    EpisodeFlags flags;
    flags.bad = f.Boolean("bad", false);
    flags.split = f.OptionalString("split", "train");
    if (flags.split != "train" && flags.split != "valid") {
      f.Fail(f.Name("split"), "must be \"train\" or \"valid\" (got \"" + flags.split + "\")");
    }
    flags.note = f.OptionalString("note", "");
    m.episode_flags[name] = flags;
  }
  return m;
}

SessionManifest LoadManifest(const std::string& path) {
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError(path + ": cannot read the session manifest (missing or unreadable)");
  return ManifestFromJson(*text, path);
}

void SaveManifest(const SessionManifest& manifest, const std::string& path) {
  WriteFileAtomically(path, ManifestToJson(manifest));
}

}  // namespace recon::store
