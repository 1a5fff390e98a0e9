#include "app/studio/studio_options.h"

#include "app/cli/option_checks.h"

namespace recon::studio {

using cli::kMaxBeaconNoise_m;
using cli::kMaxCountdown_s;
using cli::kMaxDemoNoise_rad_s;
using cli::kMaxSteps;
using cli::kMaxTests;
using cli::kMaxUiScale;
using cli::kMinUiScale;
using cli::NumberBetween;
using cli::SeedNumber;
using cli::WholeBetween;

// A teacher would not place a beacon more often; the simulated calibration's many more points
// add nothing to a rigid fit of 3 unknowns (2-D) that 100 do not.
constexpr int kMaxCalibrationPoints = 100;

CLI::Option* AddStudioOptions(CLI::App& app, StudioFlags& flags) {
  app.add_option("--session", flags.options.session_dir,
                 "session folder (created if new); without, the studio starts at the session "
                 "picker with the recent sessions");
  app.add_option("--world", flags.options.world, "task of a new session")->capture_default_str();
  app.add_option("--seed", flags.options.seed, "seed of a new session")
      ->check(SeedNumber())
      ->capture_default_str();
  app.add_option("--layout", flags.options.layout,
                 "scene layout of a new tabletop session: paper (the plate at one of two "
                 "places, 2 demonstrations per configuration) or wide")
      ->check(CLI::IsMember({"paper", "wide"}))
      ->capture_default_str();
  app.add_option("--noise", flags.options.beacon_noise_sigma,
                 "beacon noise sigma per axis of a new simulated session, metres (default: a "
                 "DWM1001's 0.07 on the tabletop)")
      ->check(NumberBetween(0, kMaxBeaconNoise_m));
  app.add_option("--demo-noise", flags.options.demo_noise_sigma,
                 "noise injected into the executed joint velocities while demonstrating in a new "
                 "session (DART, rad/s; 0 = off, the default)")
      ->check(NumberBetween(0, kMaxDemoNoise_rad_s));
  app.add_flag("--headless", flags.headless, "render through EGL without a window");
  app.add_option("--cell", flags.options.cell_profile,
                 "teach with the real devices of this cell profile (JSON: camera, beacons, UR "
                 "robot; docs/hardware.md) instead of the simulated cell")
      ->check(CLI::ExistingFile);
  app.add_option("--calibration", flags.options.calibration_file,
                 "attach this calibration (recon calibrate --out) to the session")
      ->check(CLI::ExistingFile);
  app.add_option("--dev", flags.options.dev_dir,
                 "device folder the Cell screen lists beacons, cameras and gamepads from")
      ->capture_default_str();
  app.add_option("--robot-host", flags.options.robot_hosts,
                 "a UR controller the Cell screen lists (host or host:port; repeatable)");
  app.add_flag("--fast", flags.fast,
               "record demonstrations as fast as the simulation runs (default: 10 Hz, real time)");
  app.add_option("--train-steps", flags.options.train_steps,
                 "training steps per method (default: the world's recipe: 7500 on the "
                 "tabletop)")
      ->check(WholeBetween(1, kMaxSteps));
  app.add_option("--countdown", flags.options.countdown_s,
                 "seconds counted down before a keyboard or gamepad take starts (0: at once)")
      ->check(NumberBetween(0, kMaxCountdown_s))
      ->capture_default_str();
  app.add_option("--rollout-tests", flags.options.rollout_tests, "scenes per rollout run")
      ->check(WholeBetween(1, kMaxTests))
      ->capture_default_str();
  app.add_option("--probe-grid", flags.options.probe_grid,
                 "places per side of the grid \"Check what it looks at\" moves each object over")
      ->check(WholeBetween(2, 100))
      ->capture_default_str();
  app.add_option("--calibration-points", flags.options.calibration_points,
                 "places the beacon is put at for a calibration (the simulated cell's, or a "
                 "real cell's, paced by the teacher)")
      ->check(WholeBetween(3, kMaxCalibrationPoints))
      ->capture_default_str();
  app.add_option("--script", flags.script,
                 "play a script of inputs (click <label>, type, press, wait N, wait-idle, "
                 "screenshot <file>)");
  app.add_option("--screenshots", flags.screenshots, "folder for the script's screenshots");
  app.add_option("--screenshot", flags.screenshot, "write the last frame here (PNG)");
  CLI::Option* frames =
      app.add_option("--frames", flags.frames,
                     "frames to run without a script (a window: until closed, unless given)")
          ->check(WholeBetween(1, kMaxFrames))
          ->capture_default_str();
  app.add_option("--width", flags.width, "window width")
      ->check(WholeBetween(640, 8192))
      ->capture_default_str();
  app.add_option("--height", flags.height, "window height")
      ->check(WholeBetween(480, 8192))
      ->capture_default_str();
  app.add_option("--ui-scale", flags.ui_scale,
                 "draw the font and every size this much larger (2 on a high-DPI screen); "
                 "default: the screen's own scale in a window, 1 headless")
      ->check(NumberBetween(kMinUiScale, kMaxUiScale));
  return frames;
}

}  // namespace recon::studio
