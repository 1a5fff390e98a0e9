#include "devices/cell/twin_cell.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/table_tags_file.h"
#include "engine/core/files.h"

namespace recon::cell {

std::string WriteTwinCell(const std::string& folder, const TwinCellDevices& devices,
                          const TwinLayout& layout, int width, int height) {
  namespace fs = std::filesystem;
  const fs::path dir(folder);
  fs::create_directories(dir);
  const TwinScene scene;
  WriteTwinLayout((dir / "layout.json").string(), layout);
  camera::WriteCameraCalibration(
      (dir / "camera.yaml").string(),
      camera::CameraCalibration::FromIntrinsics(scene.TopCamera(width, height).intrinsics()));
  camera::WriteTableTags((dir / "table_tags.json").string(), scene.TableTags());
  nlohmann::json names = nlohmann::json::object();
  for (const auto& [id, name] : devices.beacon_names) names[id] = name;
  const nlohmann::json profile = {
      {"camera", {{"device", "twin:layout.json"}, {"calibration", "camera.yaml"}}},
      {"table_tags", "table_tags.json"},
      {"beacons",
       {{"ports", devices.beacon_ports}, {"mode", devices.beacon_mode}, {"names", names}}},
      {"robot",
       {{"host", devices.robot_host},
        {"rtde_port", devices.rtde_port},
        {"script_port", devices.script_port}}},
      {"beacon_tag",
       {{"id", TwinScene::kBeaconTagId},
        {"size_m", scene.BeaconTagSize()},
        {"height_m", scene.BeaconTagHeight()}}}};
  const std::string path = (dir / "cell.json").string();
  WriteFileAtomically(path, profile.dump(2) + "\n");
  return path;
}

}  // namespace recon::cell
