#include "devices/cell/cell_profile.h"

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::cell {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

/// One JSON object of the profile with its dotted name ("beacons", "robot"), so every error names
/// the file and the field.
class Fields {
 public:
  Fields(const json& object, std::string file, std::string name)
      : object_(object), file_(std::move(file)), name_(std::move(name)) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const {
    throw UserError(file_ + ": " + Name(field) + ": " + problem);
  }
  std::string Name(const std::string& field) const {
    return name_.empty() ? field : name_ + "." + field;
  }
  bool Has(const std::string& field) const { return object_.contains(field); }

  /// A typo ("robto") would otherwise silently drop a device.
  void OnlyKnown(std::initializer_list<const char*> known) const {
    for (const auto& [key, value] : object_.items()) {
      bool found = false;
      std::string list;
      for (const char* k : known) {
        found = found || key == k;
        list += (list.empty() ? "" : ", ") + std::string(k);
      }
      if (!found) Fail(key, "unknown field (known here: " + list + ")");
    }
  }

  Fields Object(const std::string& field) const {
    const json& value = Get(field);
    if (!value.is_object()) Fail(field, "expected an object");
    return Fields(value, file_, Name(field));
  }
  const json& Array(const std::string& field) const {
    const json& value = Get(field);
    if (!value.is_array()) Fail(field, "expected a list");
    return value;
  }
  std::string String(const std::string& field) const {
    const json& value = Get(field);
    if (!value.is_string()) Fail(field, "expected a string");
    std::string text = value.get<std::string>();
    if (text.empty()) Fail(field, "must not be empty");
    return text;
  }
  double Number(const std::string& field) const {
    const json& value = Get(field);
    if (!value.is_number()) Fail(field, "expected a number");
    return value.get<double>();
  }
  int Port(const std::string& field) const {
    const json& value = Get(field);
    if (!value.is_number_integer() || value.get<int64_t>() < 1 || value.get<int64_t>() > 65535) {
      Fail(field, "expected a TCP port number (1-65535)");
    }
    return static_cast<int>(value.get<int64_t>());
  }
  const json& object() const { return object_; }
  const std::string& file() const { return file_; }

 private:
  const json& Get(const std::string& field) const {
    if (!object_.contains(field)) Fail(field, "missing");
    return object_.at(field);
  }

  const json& object_;
  std::string file_;
  std::string name_;
};

std::string Resolve(const fs::path& folder, const std::string& path) {
  const fs::path p(path);
  return p.is_absolute() ? path : (folder / p).lexically_normal().string();
}

/// A V4L2 index ("0") or a /dev/ path stays as given; a file or folder is the user's path.
std::string ResolveCameraDevice(const fs::path& folder, const std::string& device) {
  if (device.rfind(kTwinCameraPrefix, 0) == 0) {
    const std::string layout = device.substr(std::char_traits<char>::length(kTwinCameraPrefix));
    if (layout.empty()) throw UserError("a twin camera names its layout file: twin:layout.json");
    return kTwinCameraPrefix + Resolve(folder, layout);
  }
  bool digits = device.size() <= 4;
  for (char c : device) digits = digits && c >= '0' && c <= '9';
  if (digits || device.rfind("/dev/", 0) == 0) return device;
  return Resolve(folder, device);
}

/// "0x1A2B", "DECA0000000012AB": what BeaconHub accepts, checked here so the error names the file.
bool IsNodeIdKey(std::string key) {
  if (key.rfind("0x", 0) == 0 || key.rfind("0X", 0) == 0) key = key.substr(2);
  if (key.empty() || key.size() > 16) return false;
  return key.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
}

CameraProfile ReadCamera(const Fields& top, const fs::path& folder) {
  const Fields camera = top.Object("camera");
  camera.OnlyKnown({"device", "calibration"});
  CameraProfile profile;
  const std::string device = camera.String("device");
  try {
    profile.device = ResolveCameraDevice(folder, device);
  } catch (const UserError& e) {
    camera.Fail("device", e.what());
  }
  if (camera.Has("calibration"))
    profile.calibration = Resolve(folder, camera.String("calibration"));
  return profile;
}

BeaconsProfile ReadBeacons(const Fields& top, const fs::path& folder) {
  const Fields beacons = top.Object("beacons");
  beacons.OnlyKnown({"ports", "mode", "names"});
  BeaconsProfile profile;
  const json& ports = beacons.Array("ports");
  if (ports.empty()) beacons.Fail("ports", "needs at least one serial port");
  for (size_t i = 0; i < ports.size(); ++i) {
    const std::string field = "ports[" + std::to_string(i) + "]";
    if (!ports[i].is_string() || ports[i].get<std::string>().empty()) {
      beacons.Fail(field, "expected a string");
    }
    profile.ports.push_back(Resolve(folder, ports[i].get<std::string>()));
  }
  if (beacons.Has("mode")) {
    const std::string mode = beacons.String("mode");
    if (mode != "lec" && mode != "tlv") {
      beacons.Fail("mode", "unknown mode \"" + mode + "\" (valid: lec, tlv)");
    }
    profile.mode = uwb::ParseDwm1001Mode(mode);
  }
  if (beacons.Has("names")) {
    const Fields names = beacons.Object("names");
    for (const auto& [key, value] : names.object().items()) {
      if (!IsNodeIdKey(key)) {
        names.Fail(key, "the key must be a node id in hex, as `si` prints it (e.g. 0x1A2B)");
      }
      profile.names[key] = names.String(key);
    }
  }
  return profile;
}

RobotProfile ReadRobot(const Fields& top) {
  const Fields robot = top.Object("robot");
  robot.OnlyKnown({"host", "rtde_port", "script_port"});
  RobotProfile profile;
  profile.host = robot.String("host");
  if (robot.Has("rtde_port")) profile.rtde_port = robot.Port("rtde_port");
  if (robot.Has("script_port")) profile.script_port = robot.Port("script_port");
  return profile;
}

Eigen::Isometry3d ReadBase(const Fields& top) {
  const Fields base = top.Object("robot_base_in_table");
  base.OnlyKnown({"xyz_m", "yaw_deg"});
  Eigen::Vector3d xyz_m = Eigen::Vector3d::Zero();
  if (base.Has("xyz_m")) {
    const json& xyz = base.Array("xyz_m");
    if (xyz.size() != 3 || !xyz[0].is_number() || !xyz[1].is_number() || !xyz[2].is_number()) {
      base.Fail("xyz_m", "expected [x, y, z] in metres");
    }
    xyz_m = {xyz[0].get<double>(), xyz[1].get<double>(), xyz[2].get<double>()};
  }
  const double yaw_deg = base.Has("yaw_deg") ? base.Number("yaw_deg") : 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(xyz_m);
  pose.rotate(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  return pose;
}

BeaconTagProfile ReadBeaconTag(const Fields& top) {
  const Fields tag = top.Object("beacon_tag");
  tag.OnlyKnown({"id", "size_m", "height_m"});
  BeaconTagProfile profile;
  if (tag.Has("id")) {
    const double id = tag.Number("id");
    if (id != std::floor(id) || id < 0 || id > 586) {
      tag.Fail("id", "expected a tag36h11 id, a whole number from 0 to 586");
    }
    profile.id = static_cast<int>(id);
  }
  if (tag.Has("size_m")) {
    profile.size_m = tag.Number("size_m");
    if (!(profile.size_m > 0.005 && profile.size_m < 0.5)) {
      tag.Fail("size_m", "expected the black border's side in metres, 0.005 to 0.5");
    }
  }
  if (tag.Has("height_m")) {
    profile.height_m = tag.Number("height_m");
    if (!(profile.height_m >= 0 && profile.height_m < 1)) {
      tag.Fail("height_m", "expected the tag's height over the table in metres, 0 to 1");
    }
  }
  return profile;
}

Eigen::Vector3d ReadBeaconOnArm(const Fields& top) {
  const Fields on_arm = top.Object("beacon_on_arm");
  on_arm.OnlyKnown({"offset_m"});
  const json& xyz = on_arm.Array("offset_m");
  if (xyz.size() != 3 || !xyz[0].is_number() || !xyz[1].is_number() || !xyz[2].is_number()) {
    on_arm.Fail("offset_m", "expected [x, y, z] in metres");
  }
  const Eigen::Vector3d offset(xyz[0].get<double>(), xyz[1].get<double>(), xyz[2].get<double>());
  if (!offset.allFinite() || offset.norm() > 0.5) {
    on_arm.Fail("offset_m", "expected the beacon's offset from the tool point, within 0.5 m");
  }
  return offset;
}

}  // namespace

CellProfile ReadCellProfile(const std::string& path) {
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError(path + ": cannot read the cell profile (missing or unreadable)");
  json root;
  try {
    root = json::parse(*text);
  } catch (const json::parse_error& e) {
    throw UserError(path + ": not valid JSON (" + e.what() + ")");
  }
  if (!root.is_object()) throw UserError(path + ": expected a JSON object (a cell profile)");
  const Fields top(root, path, "");
  top.OnlyKnown({"camera", "table_tags", "beacons", "robot", "robot_base_in_table", "beacon_tag",
                 "beacon_on_arm"});
  const fs::path folder = fs::absolute(fs::path(path)).parent_path();

  CellProfile profile;
  profile.path = path;
  profile.camera = ReadCamera(top, folder);
  profile.table_tags = Resolve(folder, top.String("table_tags"));
  profile.beacons = ReadBeacons(top, folder);
  if (top.Has("robot")) profile.robot = ReadRobot(top);
  if (top.Has("robot_base_in_table")) profile.robot_base_in_table = ReadBase(top);
  if (top.Has("beacon_tag")) profile.beacon_tag = ReadBeaconTag(top);
  if (top.Has("beacon_on_arm")) {
    if (!profile.robot) top.Fail("beacon_on_arm", "a beacon on the arm needs a robot");
    profile.beacon_on_arm_offset_m = ReadBeaconOnArm(top);
  }
  return profile;
}

}  // namespace recon::cell
