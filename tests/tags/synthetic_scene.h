#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "engine/core/image.h"

namespace recon::tags::testing {

/// A camera described the way MuJoCo describes one, deliberately NOT through
/// recon::tags::PinholeCamera, so the tests check that class's conventions against an
/// independent formulation: vertical fov, image size, position, and orientation whose columns
/// are the camera's x (right), y (up in the image) and z (backwards: it looks along -z) axes.
struct SceneCamera {
  double fovy_deg = 60.0;
  int width = 640;
  int height = 480;
  Eigen::Vector3d position_m{0.0, 0.0, 1.0};
  Eigen::Matrix3d table_R_mujoco = Eigen::Matrix3d::Identity();
};

/// A tag36h11 lying flat (face up) on the horizontal plane through `center_m`. With yaw 0 its top
/// row faces table +y and its bitmap's columns run along +x, as a printed tag seen from above.
struct PlacedTag {
  int id = 0;
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  double size_m = 0.06;  ///< black border's outer edge; the white quiet zone adds a cell each side
};

/// An axis-aligned grey box in image pixels [col0, col1) x [row0, row1) drawn over everything:
/// an object between the camera and the table.
struct Occluder {
  int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
  uint8_t grey = 90;
};

struct SceneOptions {
  /// false: a uniformly white table; true: a wood-like grey texture (table-fixed, so it moves
  /// with perspective like a real surface) between about 110 and 210.
  bool textured_table = false;
  /// Per pixel additive Gaussian noise on the grey level (0 = none).
  double noise_sigma = 0.0;
  /// Samples per pixel along each axis (area anti-aliasing as a multisampled render would do).
  int supersample = 4;
  uint64_t seed = 1;  ///< texture phases and noise
};

/// Renders the table and tags by inverse mapping: every sample point at (col + (i + 0.5) / n,
/// row + (j + 0.5) / n) - pixel (c, r) covering [c, c + 1) x [r, r + 1), as OpenGL samples - is
/// cast into the scene, hits the nearest tag plane whose bitmap covers it or else the table
/// (z = 0), and takes that grey level (nearest cell); the samples are averaged.
RgbImage RenderScene(const SceneCamera& camera, const std::vector<PlacedTag>& tags,
                     const std::vector<Occluder>& occluders, const SceneOptions& options);

/// Where a table-frame point lands in the image, computed the same independent way.
Eigen::Vector2d ProjectPoint(const SceneCamera& camera, const Eigen::Vector3d& point_m);

/// The four outer corners of the black border in the table frame, in the order
/// (-1, -1), (1, -1), (1, 1), (-1, 1) of tag-local (x right, y toward the top row) units.
std::vector<Eigen::Vector3d> TagCorners(const PlacedTag& tag);

}  // namespace recon::tags::testing
