#include "app/cli/cell_commands.h"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/device_calibrate.h"
#include "app/cli/option_checks.h"
#include "app/cli/output_path.h"
#include "devices/cell/sim_calibration.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/core/progress.h"
#include "engine/core/strings.h"
#include "engine/report/image_png.h"
#include "engine/worlds/bintransfer.h"
#include "engine/worlds/scene_assets.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/tag_textures.h"

namespace recon::cli {

namespace {

struct RenderFlags {
  std::string scene = "tabletop";
  std::string camera;
  uint64_t seed = 1;
  int width = 640;
  int height = 480;
  std::string out;
  bool force = false;
};

void RunRender(const RenderFlags& flags) {
  CheckOutputFile("--out", flags.out, flags.force);
  // Every renderer the factory makes on this thread shares one EGL context, the world's too.
  const worlds::SceneRendererFactory make_renderer = render::MujocoRendererFactory();
  const std::unique_ptr<worlds::SceneRenderer> renderer = make_renderer();
  RgbImage image;
  if (flags.scene == "tabletop") {
    // The world lays the scene out from the seed (plate side, bowl, toast), exactly as an
    // experiment's scenario with that seed.
    worlds::TabletopOptions options;
    options.placement = "none";
    worlds::Tabletop world(options, make_renderer());
    world.Reset(flags.seed);
    image = renderer->Render(world.scene(), flags.camera.empty() ? "top" : flags.camera,
                             flags.width, flags.height);
  } else if (flags.scene == "bintransfer") {
    worlds::BinTransfer world("none", 0.0);
    world.Reset(flags.seed);
    image = renderer->Render(world.scene(), flags.camera.empty() ? "overhead" : flags.camera,
                             flags.width, flags.height);
  } else {
    worlds::MujocoModel scene = worlds::LoadScene(flags.scene);
    worlds::PaintTagTextures(scene);
    mj_forward(scene.model(), scene.data());  // cameras and bodies where the model puts them
    image = renderer->Render(scene, flags.camera.empty() ? "top" : flags.camera, flags.width,
                             flags.height);
  }
  report::WritePng(image, flags.out);
  std::printf("wrote %s (%d x %d, scene %s, seed %llu)\n", flags.out.c_str(), image.width,
              image.height, flags.scene.c_str(), static_cast<unsigned long long>(flags.seed));
}

struct CalibrateFlags {
  bool sim = false;
  DeviceCalibrateFlags device;
  int points = 12;
  uint64_t seed = 1;
  std::string dimension = "2d";
  double threshold_m = 0.10;
  std::string out;
  bool force = false;
};

void RunCalibrate(const CalibrateFlags& flags) {
  if (!flags.out.empty()) CheckOutputFile("--out", flags.out, flags.force);
  cell::SimCalibrationOptions options;
  options.points = flags.points;
  options.seed = flags.seed;
  options.calibration.pass_rmse_m = flags.threshold_m;
  if (flags.dimension == "2d") {
    options.calibration.dimension = calib::FitDimension::k2D;
  } else if (flags.dimension == "3d") {
    options.calibration.dimension = calib::FitDimension::k3D;
  } else {
    throw UserError("--dim must be 2d or 3d (got '" + flags.dimension + "')");
  }
  if (!flags.sim) {
    const calib::CalibrationReport report =
        RunDeviceCalibrate(flags.device, flags.points, options.calibration);
    if (!flags.out.empty()) {
      calib::SaveCalibration(report, flags.out);
      std::printf("wrote %s\n", flags.out.c_str());
    }
    return;
  }
  std::printf("recon calibrate --sim: %d beacon poses in the simulated tabletop cell, seed %llu\n",
              flags.points, static_cast<unsigned long long>(flags.seed));
  std::fflush(stdout);  // the progress line goes to stderr; keep the two in order
  ProgressLine progress("calibrating", flags.points);
  const cell::SimCalibrationResult result =
      cell::RunSimulatedCalibration(options, [&](int, int) { progress.Advance(); });
  progress.Finish();
  std::printf("%s", cell::Describe(result).c_str());
  if (!flags.out.empty()) {
    calib::SaveCalibration(result.report, flags.out);
    std::printf("wrote %s\n", flags.out.c_str());
  }
}

}  // namespace

void AddCellCommands(CLI::App& app) {
  auto render_flags = std::make_shared<RenderFlags>();
  CLI::App* render = app.add_subcommand("render", "write one camera image of a simulated scene");
  render
      ->add_option(
          "--scene", render_flags->scene,
          "a scene (" + JoinNames(worlds::SceneNames()) + ") or an MJCF file ending in .xml")
      ->capture_default_str();
  render->add_option("--camera", render_flags->camera,
                     "camera name (default: top; overhead for bintransfer)");
  render->add_option("--seed", render_flags->seed, "scenario seed (tabletop, bintransfer layout)")
      ->check(SeedNumber())
      ->capture_default_str();
  render->add_option("--width", render_flags->width, "image width")
      ->check(WholeBetween(1, kMaxImageSide))
      ->capture_default_str();
  render->add_option("--height", render_flags->height, "image height")
      ->check(WholeBetween(1, kMaxImageSide))
      ->capture_default_str();
  render->add_option("--out", render_flags->out, "PNG file to write")->required();
  AddForceFlag(*render, render_flags->force);
  render->callback([render_flags] { RunRender(*render_flags); });

  auto cal_flags = std::make_shared<CalibrateFlags>();
  CLI::App* calibrate =
      app.add_subcommand("calibrate", "fit the UWB frame to the table frame from AprilTags");
  calibrate->add_flag("--sim", cal_flags->sim, "calibrate in the simulated cell");
  calibrate->add_option("--points", cal_flags->points, "static beacon poses to collect")
      ->check(WholeBetween(3, 1000))
      ->capture_default_str();
  calibrate->add_option("--seed", cal_flags->seed, "seed of poses, UWB noise and hidden frame")
      ->check(SeedNumber())
      ->capture_default_str();
  calibrate->add_option("--dim", cal_flags->dimension, "2d (planar) or 3d fit")
      ->capture_default_str();
  calibrate->add_option("--threshold", cal_flags->threshold_m, "pass if RMSE is at most this (m)")
      ->check(PositiveNumberUpTo(1.0))
      ->capture_default_str();
  calibrate->add_option("--out", cal_flags->out, "save the calibration (JSON) here");
  AddForceFlag(*calibrate, cal_flags->force);
  DeviceCalibrateFlags& device = cal_flags->device;
  calibrate->add_option("--camera", device.camera,
                        "real devices: the camera (/dev/videoN, index, video file, image folder)");
  calibrate
      ->add_option("--camera-calibration", device.camera_calibration,
                   "real devices: the camera's OpenCV calibration YAML")
      ->check(CLI::ExistingFile);
  calibrate
      ->add_option("--table-tags", device.table_tags,
                   "real devices: JSON of the AprilTags taped to the table (ids, places)")
      ->check(CLI::ExistingFile);
  calibrate->add_option("--beacon-port", device.beacon_ports,
                        "real devices: a DWM1001's serial port (repeatable)");
  calibrate->add_option("--name", device.names, "real devices: NODE_ID=name (repeatable)");
  calibrate->add_option("--beacon", device.beacon, "the beacon that carries the tag, by name");
  calibrate->add_option("--mode", device.mode, "DWM1001 mode: lec or tlv")->capture_default_str();
  calibrate->add_option("--beacon-tag-id", device.beacon_tag_id, "the beacon's AprilTag id")
      ->check(WholeBetween(0, 586))  // tag36h11
      ->capture_default_str();
  calibrate
      ->add_option("--beacon-tag-size", device.beacon_tag_size_m, "its black border's side (m)")
      ->check(PositiveNumberUpTo(1.0))
      ->capture_default_str();
  calibrate
      ->add_option("--beacon-tag-height", device.beacon_tag_height_m,
                   "its face's height over the table (m)")
      ->check(NumberBetween(0, 2.0))
      ->capture_default_str();
  calibrate->add_option("--frames", device.frames, "camera frames averaged per pose")
      ->check(WholeBetween(1, 1000))
      ->capture_default_str();
  calibrate->add_option("--uwb-samples", device.uwb_samples, "beacon positions averaged per pose")
      ->check(WholeBetween(1, 100000))
      ->capture_default_str();
  calibrate->add_flag("--no-wait", device.no_wait,
                      "do not wait for Enter between poses (the beacon is moved by a script)");
  calibrate->callback([cal_flags] { RunCalibrate(*cal_flags); });
}

}  // namespace recon::cli
