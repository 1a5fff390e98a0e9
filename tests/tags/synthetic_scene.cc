#include "tests/tags/synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/rng.h"
#include "engine/worlds/tag_bitmap.h"

namespace recon::tags::testing {
namespace {

double FocalPx(const SceneCamera& camera) {
  return 0.5 * camera.height / std::tan(0.5 * camera.fovy_deg * M_PI / 180.0);
}

// The table-frame direction of the ray through image point (u, v), u right and v down from the
// top-left corner of the image, following MuJoCo: the image centre is the optical axis, the
// camera looks along its -z and its +y is up in the image.
Eigen::Vector3d RayThrough(const SceneCamera& camera, double f, double u, double v) {
  const Eigen::Vector3d in_camera((u - 0.5 * camera.width) / f, -(v - 0.5 * camera.height) / f,
                                  -1.0);
  return camera.table_R_mujoco * in_camera;
}

struct TagRaster {
  PlacedTag placed;
  worlds::TagImage cells;  // 10 x 10, one pixel per cell
  double cos_yaw, sin_yaw, cell_m, half_extent_m;
};

// A wood-like grain: a few table-fixed sinusoids with seeded phases, kept between about 110 and
// 210 so black borders stand out and the white quiet zone is brighter still.
struct TableTexture {
  explicit TableTexture(uint64_t seed) {
    Rng rng(seed);
    for (double& p : phase) p = rng.Uniform(0.0, 2.0 * M_PI);
  }
  double At(double x, double y) const {
    const double grain =
        std::sin(2.0 * M_PI * (y * 37.0 + 0.8 * std::sin(x * 9.0 + phase[0])) + phase[1]);
    const double fine = std::sin(2.0 * M_PI * (x * 113.0 + y * 17.0) + phase[2]);
    const double blotch = std::sin(x * 5.0 + phase[3]) * std::cos(y * 4.0 + phase[4]);
    return 160.0 + 30.0 * grain + 8.0 * fine + 12.0 * blotch;
  }
  double phase[5];
};

}  // namespace

Eigen::Vector2d ProjectPoint(const SceneCamera& camera, const Eigen::Vector3d& point_m) {
  const double f = FocalPx(camera);
  const Eigen::Vector3d p = camera.table_R_mujoco.transpose() * (point_m - camera.position_m);
  // In front of a MuJoCo camera means p.z() < 0.
  return {0.5 * camera.width + f * p.x() / -p.z(), 0.5 * camera.height - f * p.y() / -p.z()};
}

std::vector<Eigen::Vector3d> TagCorners(const PlacedTag& tag) {
  const double half = 0.5 * tag.size_m;
  const double c = std::cos(tag.yaw_rad), s = std::sin(tag.yaw_rad);
  std::vector<Eigen::Vector3d> corners;
  const double local[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
  for (const auto& [lx, ly] : local) {
    corners.push_back(tag.center_m +
                      Eigen::Vector3d(half * (c * lx - s * ly), half * (s * lx + c * ly), 0.0));
  }
  return corners;
}

RgbImage RenderScene(const SceneCamera& camera, const std::vector<PlacedTag>& tags,
                     const std::vector<Occluder>& occluders, const SceneOptions& options) {
  std::vector<TagRaster> rasters;
  for (const PlacedTag& tag : tags) {
    const double cell_m = tag.size_m / worlds::kTagBlackCells;
    rasters.push_back({tag, worlds::TagBitmap(tag.id, 1), std::cos(tag.yaw_rad),
                       std::sin(tag.yaw_rad), cell_m, 0.5 * worlds::kTagGridCells * cell_m});
  }
  const TableTexture texture(Rng::Derive(options.seed, 0));
  Rng noise(Rng::Derive(options.seed, 1));
  const double f = FocalPx(camera);
  const int n = std::max(1, options.supersample);

  // The grey level seen along one ray: the nearest tag whose bitmap (quiet zone included) it
  // crosses, else the table top at z = 0.
  auto sample = [&](const Eigen::Vector3d& direction) {
    double nearest = std::numeric_limits<double>::infinity();
    double grey = 255.0;
    for (const TagRaster& r : rasters) {
      const double t = (r.placed.center_m.z() - camera.position_m.z()) / direction.z();
      if (!(t > 0.0) || t >= nearest) continue;
      const Eigen::Vector3d d = camera.position_m + t * direction - r.placed.center_m;
      const double lx = r.cos_yaw * d.x() + r.sin_yaw * d.y();
      const double ly = -r.sin_yaw * d.x() + r.cos_yaw * d.y();
      const int col = static_cast<int>(std::floor((lx + r.half_extent_m) / r.cell_m));
      const int row = static_cast<int>(std::floor((r.half_extent_m - ly) / r.cell_m));
      if (col < 0 || col >= r.cells.size || row < 0 || row >= r.cells.size) continue;
      nearest = t;
      grey = r.cells.At(row, col);
    }
    if (std::isinf(nearest)) {
      const double t = -camera.position_m.z() / direction.z();
      if (t > 0.0) {
        const Eigen::Vector3d hit = camera.position_m + t * direction;
        grey = options.textured_table ? texture.At(hit.x(), hit.y()) : 255.0;
      }
    }
    return grey;
  };

  RgbImage image;
  image.width = camera.width;
  image.height = camera.height;
  image.rgb.resize(static_cast<size_t>(image.width) * image.height * 3);
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      double sum = 0.0;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          sum += sample(RayThrough(camera, f, col + (i + 0.5) / n, row + (j + 0.5) / n));
        }
      }
      double grey = sum / (n * n);
      for (const Occluder& o : occluders) {
        if (col >= o.col0 && col < o.col1 && row >= o.row0 && row < o.row1) grey = o.grey;
      }
      if (options.noise_sigma > 0.0) grey += options.noise_sigma * noise.Normal();
      const auto value = static_cast<uint8_t>(std::clamp(std::lround(grey), 0L, 255L));
      uint8_t* pixel = image.rgb.data() + (static_cast<size_t>(row) * image.width + col) * 3;
      pixel[0] = pixel[1] = pixel[2] = value;
    }
  }
  return image;
}

}  // namespace recon::tags::testing
