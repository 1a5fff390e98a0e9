#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace recon::camera {

/// A tag fixed at a known place in the table frame, lying flat and face up (a printed tag taped
/// to the table top or a raised plate). Its corners follow tests/tags/synthetic_scene.h and
/// libapriltag: tag-local x to the right of the printed tag, y toward its top row.
struct TableTag {
  int id = -1;
  Eigen::Vector3d center_table_m = Eigen::Vector3d::Zero();
  /// Side of the black border's outer edge (8 of tag36h11's 10 cells), metres.
  double size_m = 0.0;
  /// Rotation of the tag about table +z: 0 puts its top row toward table +y.
  double yaw_rad = 0.0;

  /// The four outer corners of the black border in the table frame, in the order of
  /// tags::TagDetection::corners_px: tag-local (-1, -1), (1, -1), (1, 1), (-1, 1).
  std::vector<Eigen::Vector3d> Corners() const;
};

/// Reads a "table tags" JSON file:
///   {"tags": [{"id": 0, "center_m": [0.10, -0.40, 0.0], "size_m": 0.048, "yaw_deg": 0}, ...]}
/// (yaw_deg optional, default 0). Throws UserError naming the file and the entry/field that is
/// missing or wrong, for duplicate ids, and for a file that is not JSON.
std::vector<TableTag> ReadTableTags(const std::string& path);

/// Writes `tags` in the format ReadTableTags reads, atomically.
void WriteTableTags(const std::string& path, const std::vector<TableTag>& tags);

}  // namespace recon::camera
