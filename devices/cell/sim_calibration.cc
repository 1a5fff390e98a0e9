#include "devices/cell/sim_calibration.h"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "devices/cell/calibration_collector.h"
#include "devices/cell/scene_camera.h"
#include "devices/render/mujoco_renderer.h"
#include "devices/sim/hidden_uwb_frame.h"
#include "devices/tags/pinhole_camera.h"
#include "devices/tags/table_locator.h"
#include "devices/tags/tag_detector.h"
#include "devices/uwb/lec_parser.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/worlds/scene_assets.h"
#include "engine/worlds/tag_textures.h"

namespace recon::cell {

namespace {

constexpr char kCamera[] = "top";
constexpr int kBeaconTagId = 10;
// The beacon tag: a 4.4 cm textured square whose black border is 0.8 of it, on the beacon's top.
constexpr double kBeaconTagSize_m = 0.044 * 0.8;
// Where the teacher puts the plate (and so the beacon beside it): the reachable table area.
constexpr double kMinX = 0.25, kMaxX = 0.85, kMaxAbsY = 0.38;
// Seed streams, so that changing the number of points keeps the hidden frame.
constexpr uint64_t kFrameStream = 1, kPoseStream = 2, kUwbStream = 3;

Eigen::Vector3d Vec(const mjtNum* p) { return {p[0], p[1], p[2]}; }

}  // namespace

SimCalibrationResult RunSimulatedCalibration(const SimCalibrationOptions& options,
                                             const CalibrationProgress& progress) {
  if (options.points < 3) throw UserError("--points must be at least 3 for a rigid fit");
  if (options.updates_per_point < 1) throw UserError("updates per point must be positive");
  SimCalibrationResult result;
  Rng frame_rng(Rng::Derive(options.seed, kFrameStream));
  Rng pose_rng(Rng::Derive(options.seed, kPoseStream));
  result.hidden_table_to_uwb = sim::DrawHiddenUwbFrame(frame_rng);

  worlds::MujocoModel scene = worlds::LoadScene("tabletop");
  worlds::PaintTagTextures(scene);
  const mjModel* m = scene.model();
  mjData* d = scene.data();
  const int plate = mj_name2id(m, mjOBJ_BODY, "plate");
  const int bowl = mj_name2id(m, mjOBJ_BODY, "bowl");
  const int beacon_site = mj_name2id(m, mjOBJ_SITE, "beacon");
  // Keep the bowl out of the way: calibration is done on a clear table.
  mjtNum* bowl_pos = d->mocap_pos + 3 * m->body_mocapid[bowl];
  bowl_pos[0] = 0.1;
  bowl_pos[1] = -0.5;
  mj_forward(m, d);

  // The calling thread's shared renderer (one EGL context per thread for its whole life), not a
  // new one: making and dropping contexts while other threads render is what to avoid.
  const std::unique_ptr<worlds::SceneRenderer> renderer = render::MujocoRendererFactory()();
  tags::TagDetector detector;
  const tags::PinholeCamera pinhole =
      SceneCamera(scene, kCamera, options.camera_width, options.camera_height);
  tags::TableLocator locator(pinhole, tags::TagSpec{0.048, 0.0});
  const double beacon_height = d->site_xpos[3 * beacon_site + 2];
  locator.SetTagSpec(kBeaconTagId, tags::TagSpec{kBeaconTagSize_m, beacon_height});

  uwb::SimulatedDwm1001Options uwb_options;
  uwb_options.table_to_uwb = result.hidden_table_to_uwb;
  uwb_options.seed = Rng::Derive(options.seed, kUwbStream);
  uwb::SimulatedDwm1001 beacon(uwb_options);
  uwb::LecLineParser parser;

  double tag_sq_error = 0.0;
  std::vector<calib::CalibrationPoint> points;
  for (int i = 0; i < options.points; ++i) {
    Eigen::Vector3d truth;
    std::optional<tags::TagLocation> located;
    for (int placement = 0; !located; ++placement) {
      if (placement == kPlacementsPerPoint) {
        char where[96];
        std::snprintf(where, sizeof(where), "(%.3f, %.3f)", truth.x(), truth.y());
        throw UserError(std::string("calibration point ") + std::to_string(i + 1) +
                        ": the camera did not see the beacon's tag " +
                        std::to_string(kBeaconTagId) + " at any of " +
                        std::to_string(kPlacementsPerPoint) + " places (the last " + where +
                        "): check that the camera sees the table");
      }
      mjtNum* plate_pos = d->mocap_pos + 3 * m->body_mocapid[plate];
      plate_pos[0] = pose_rng.Uniform(kMinX, kMaxX);
      plate_pos[1] = pose_rng.Uniform(-kMaxAbsY, kMaxAbsY - 0.13);  // the beacon sits at +13 cm y
      mj_forward(m, d);
      truth = Vec(d->site_xpos + 3 * beacon_site);
      const RgbImage frame =
          renderer->Render(scene, kCamera, options.camera_width, options.camera_height);
      located = LocateTag(detector, locator, frame, kBeaconTagId);
      // Unseen (out of the camera's view, or hidden): move the beacon, as a teacher
      // would, and say so.
      if (!located) result.replaced_unseen.emplace_back(truth.x(), truth.y());
    }

    std::vector<uwb::UwbReading> readings;
    for (int u = 0; u < options.updates_per_point; ++u)
      parser.Feed(beacon.NextUpdate(truth), readings);
    Eigen::Vector3d uwb_sum = Eigen::Vector3d::Zero();
    int uwb_count = 0;
    for (const auto& r : readings) {
      if (!r.has_position) continue;
      uwb_sum += Eigen::Vector3d(r.x_m, r.y_m, r.z_m);
      ++uwb_count;
    }
    if (uwb_count == 0) {
      throw UserError("calibration point " + std::to_string(i + 1) +
                      ": the UWB beacon reported no position in " +
                      std::to_string(options.updates_per_point) + " updates");
    }
    SimCalibrationSample sample;
    sample.true_table_m = truth;
    sample.point.tag_m = located->position_table_m;
    sample.point.uwb_m = uwb_sum / uwb_count;
    sample.uwb_readings = uwb_count;
    tag_sq_error += (located->position_table_m - truth).squaredNorm();
    result.samples.push_back(sample);
    points.push_back(sample.point);
    if (progress) progress(i + 1, options.points);
  }
  result.tag_rms_error_m = std::sqrt(tag_sq_error / options.points);
  result.uwb_lines = parser.stats().lines;
  result.uwb_malformed = parser.stats().malformed;
  result.uwb_dropped = beacon.dropped();
  result.uwb_garbled = beacon.garbled();

  result.report = calib::Calibrate(points, options.calibration);

  // How far the fitted UWB->table map is from the truth, over the table area, in the plane.
  double sum = 0.0, worst = 0.0;
  int n = 0;
  for (double x = kMinX; x <= kMaxX + 1e-9; x += 0.05) {
    for (double y = -kMaxAbsY; y <= kMaxAbsY + 1e-9; y += 0.05) {
      const Eigen::Vector3d p(x, y, beacon_height);
      const Eigen::Vector3d back =
          result.report.transform.Apply(result.hidden_table_to_uwb.Apply(p));
      const double e = (back - p).head<2>().norm();
      sum += e;
      worst = std::max(worst, e);
      ++n;
    }
  }
  result.offset_error_mean_m = sum / n;
  result.offset_error_max_m = worst;
  const double hidden_yaw = result.hidden_table_to_uwb.YawRad();
  result.yaw_error_rad = std::remainder(result.report.transform.YawRad() + hidden_yaw, 2 * M_PI);
  return result;
}

std::string Describe(const SimCalibrationResult& result) {
  std::ostringstream out;
  out << result.report.Summary() << "\n";
  char line[256];
  for (const Eigen::Vector2d& p : result.replaced_unseen) {
    std::snprintf(line, sizeof(line),
                  "the camera did not see the beacon's tag at (%.3f, %.3f): the beacon was moved "
                  "to another place\n",
                  p.x(), p.y());
    out << line;
  }
  std::snprintf(line, sizeof(line),
                "hidden UWB frame recovered: offset error over the table mean %.4f m, max %.4f m; "
                "heading error %.2f deg\n",
                result.offset_error_mean_m, result.offset_error_max_m,
                result.yaw_error_rad * 180.0 / M_PI);
  out << line;
  std::snprintf(line, sizeof(line),
                "camera tags vs simulator truth: %.4f m RMS over %zu poses\n"
                "UWB lines: %lld parsed into readings, %lld malformed; the beacon dropped %lld "
                "and garbled %lld updates\n",
                result.tag_rms_error_m, result.samples.size(),
                static_cast<long long>(result.uwb_lines - result.uwb_malformed),
                static_cast<long long>(result.uwb_malformed),
                static_cast<long long>(result.uwb_dropped),
                static_cast<long long>(result.uwb_garbled));
  out << line;
  return out.str();
}

}  // namespace recon::cell
