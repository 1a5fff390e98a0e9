#include "devices/camera/table_tags_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::camera {

std::vector<Eigen::Vector3d> TableTag::Corners() const {
  const double half = 0.5 * size_m;
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const double local[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
  std::vector<Eigen::Vector3d> corners;
  for (const auto& [lx, ly] : local) {
    corners.push_back(center_table_m +
                      Eigen::Vector3d(half * (c * lx - s * ly), half * (s * lx + c * ly), 0.0));
  }
  return corners;
}

std::vector<TableTag> ReadTableTags(const std::string& path) {
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError("cannot read the table tags file " + path);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError(path + ": not valid JSON (" + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("tags") || !doc["tags"].is_array()) {
    throw UserError(path + ": expected an object with a \"tags\" list");
  }
  std::vector<TableTag> tags;
  std::set<int> ids;
  for (size_t i = 0; i < doc["tags"].size(); ++i) {
    const nlohmann::json& entry = doc["tags"][i];
    const std::string where = path + ": tags[" + std::to_string(i) + "]";
    if (!entry.is_object()) throw UserError(where + " is not an object");
    TableTag tag;
    if (!entry.contains("id") || !entry["id"].is_number_integer() || entry["id"].get<int>() < 0) {
      throw UserError(where + ": \"id\" must be a non-negative integer");
    }
    tag.id = entry["id"].get<int>();
    const nlohmann::json& center = entry.value("center_m", nlohmann::json());
    if (!center.is_array() || center.size() != 3 || !center[0].is_number() ||
        !center[1].is_number() || !center[2].is_number()) {
      throw UserError(where + ": \"center_m\" must be [x, y, z] in metres");
    }
    tag.center_table_m = {center[0].get<double>(), center[1].get<double>(),
                          center[2].get<double>()};
    if (!entry.contains("size_m") || !entry["size_m"].is_number() ||
        !(entry["size_m"].get<double>() > 0.0)) {
      throw UserError(where + ": \"size_m\" must be a positive number (black border, metres)");
    }
    tag.size_m = entry["size_m"].get<double>();
    if (entry.contains("yaw_deg")) {
      if (!entry["yaw_deg"].is_number()) throw UserError(where + ": \"yaw_deg\" must be a number");
      tag.yaw_rad = entry["yaw_deg"].get<double>() * M_PI / 180.0;
    }
    if (!ids.insert(tag.id).second) {
      throw UserError(where + ": tag id " + std::to_string(tag.id) + " is listed twice");
    }
    tags.push_back(tag);
  }
  if (tags.empty()) throw UserError(path + ": the \"tags\" list is empty");
  return tags;
}

void WriteTableTags(const std::string& path, const std::vector<TableTag>& tags) {
  nlohmann::json list = nlohmann::json::array();
  for (const TableTag& tag : tags) {
    list.push_back(
        {{"id", tag.id},
         {"center_m", {tag.center_table_m.x(), tag.center_table_m.y(), tag.center_table_m.z()}},
         {"size_m", tag.size_m},
         {"yaw_deg", tag.yaw_rad * 180.0 / M_PI}});
  }
  WriteFileAtomically(path, nlohmann::json{{"tags", list}}.dump(2) + "\n");
}

}  // namespace recon::camera
