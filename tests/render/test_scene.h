#pragma once

// A small scene whose pixels can be predicted by hand: a camera 2 m above a grey floor looking
// straight down (MuJoCo cameras look along their -z axis with +y up, so the image's right is
// world +x and its top is world +y), a red box that moves (mocap) and a green box near the top
// edge of the view. Materials have no specular highlight, so colours stay clearly separable. The
// light comes in slanted towards +x so that a shadow, if drawn, would show beside the boxes.

#include <cmath>
#include <string>

#include "engine/core/image.h"

namespace recon::render::testing {

inline constexpr char kTestScene[] = R"(
<mujoco model="render test">
  <visual>
    <global offwidth="640" offheight="480"/>
    <quality offsamples="0" shadowsize="1024"/>
  </visual>
  <asset>
    <material name="grey" rgba="0.5 0.5 0.5 1" specular="0"/>
    <material name="red" rgba="1 0 0 1" specular="0"/>
    <material name="green" rgba="0 1 0 1" specular="0"/>
  </asset>
  <worldbody>
    <light directional="true" pos="-0.5 0 1" dir="1 0 -1" castshadow="true"/>
    <geom name="floor" type="plane" size="1.5 1.5 0.1" material="grey"/>
    <camera name="top" pos="0 0 2" fovy="45"/>
    <camera name="side" pos="2 0 0.5" xyaxes="0 1 0 -0.2 0 1"/>
    <body name="red_box" mocap="true" pos="0.3 -0.2 0.05">
      <geom type="box" size="0.08 0.08 0.05" material="red"/>
    </body>
    <body name="green_box" pos="0 0.6 0.05">
      <geom type="box" size="0.06 0.06 0.05" material="green"/>
    </body>
  </worldbody>
</mujoco>
)";

inline constexpr double kCameraHeight_m = 2.0;
inline constexpr double kFovY_rad = 45.0 * M_PI / 180.0;
inline constexpr double kBoxTop_m = 0.1;

/// Where the world point (x, y, z) lands in a width x height image of camera "top", as
/// fractional (row, col) with row 0 at the top.
struct PixelPosition {
  double row;
  double col;
};
inline PixelPosition ProjectTop(double x, double y, double z, int width, int height) {
  const double half_height_m = (kCameraHeight_m - z) * std::tan(kFovY_rad / 2);
  const double half_width_m = half_height_m * width / height;
  return {(1.0 - y / half_height_m) / 2.0 * height, (1.0 + x / half_width_m) / 2.0 * width};
}

inline bool IsRed(const uint8_t* p) { return p[0] > 100 && p[1] < 40 && p[2] < 40; }
inline bool IsGreen(const uint8_t* p) { return p[1] > 100 && p[0] < 40 && p[2] < 40; }
inline bool IsGrey(const uint8_t* p) {
  return p[0] > 30 && std::abs(p[0] - p[1]) < 12 && std::abs(p[0] - p[2]) < 12;
}

/// The pixels passing `test`: how many, and their centre in (row, col) pixel coordinates where
/// pixel (r, c) covers [r, r+1) x [c, c+1).
struct Blob {
  int count = 0;
  double row = 0;
  double col = 0;
};
template <typename Test>
Blob FindBlob(const RgbImage& image, Test test) {
  Blob blob;
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      if (!test(image.Pixel(r, c))) continue;
      ++blob.count;
      blob.row += r + 0.5;
      blob.col += c + 0.5;
    }
  }
  if (blob.count > 0) {
    blob.row /= blob.count;
    blob.col /= blob.count;
  }
  return blob;
}

}  // namespace recon::render::testing
