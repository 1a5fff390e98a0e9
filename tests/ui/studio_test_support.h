#pragma once

// Snapshots of a teaching session at each workflow step, made from facts (no cell, no disk), for
// the studio's screenshot and command tests.

#include <cmath>

#include "engine/teach/workflow.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::ui::testing {

/// A 160 x 120 stand-in for the top camera: a wooden table, a white plate, a blue bowl and the
/// toast, drawn from formulas so the goldens never depend on MuJoCo's rendering.
inline RgbImage SyntheticCamera() {
  RgbImage image;
  image.width = 160;
  image.height = 120;
  image.rgb.resize(160 * 120 * 3);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      uint8_t* p = image.rgb.data() + (y * 160 + x) * 3;
      const int grain = (x * 7 + y * 3) % 11;
      p[0] = static_cast<uint8_t>(176 + grain);
      p[1] = static_cast<uint8_t>(134 + grain);
      p[2] = static_cast<uint8_t>(90 + grain / 2);
      if (std::hypot(x - 110, y - 60) < 22) p[0] = p[1] = p[2] = 240;  // plate
      if (std::hypot(x - 45, y - 35) < 14) {                           // bowl
        p[0] = 40;
        p[1] = 90;
        p[2] = 170;
      }
      if (x > 40 && x < 58 && y > 78 && y < 94) {  // toast
        p[0] = 210;
        p[1] = 160;
        p[2] = 70;
      }
    }
  }
  return image;
}

/// How far a session has come.
enum class Progress { kNothing, kCellUp, kBeaconAssigned, kCalibrated, kRecorded, kTrained, kDone };

inline teach::WorkflowFacts FactsAt(Progress progress) {
  teach::WorkflowFacts f;
  const int p = static_cast<int>(progress);
  f.session_open = p >= 1;
  f.cell_connected = p >= 1;
  f.beacons_required = 1;
  f.beacons_assigned = p >= 2 ? 1 : 0;
  if (p < 2) f.unmarked_objects = {"the plate"};
  f.calibration_present = p >= 3;
  f.calibration_passed = p >= 3;
  f.calibration_rmse_m = 0.0292;
  f.demos = p >= 4 ? 4 : 0;
  f.demo_seconds = p >= 4 ? 54.0 : 0;
  f.min_demos = 1;
  f.play_samples = p >= 4 ? 40 : 0;
  if (p >= 5) f.trained_methods = {"baseline", "recon"};
  if (p >= 6) f.evaluated_methods = {"baseline", "recon"};
  return f;
}

/// The snapshot the studio would show at `progress`, on `step`'s screen.
inline StudioSnapshot SnapshotAt(Progress progress, teach::Step step) {
  const teach::WorkflowFacts facts = FactsAt(progress);
  const int p = static_cast<int>(progress);
  StudioSnapshot s;
  s.session_open = facts.session_open;
  s.session_dir = facts.session_open ? "sessions/toast" : "";
  s.world = "tabletop";
  s.steps = teach::EvaluateWorkflow(facts);
  for (int i = 0; i < teach::kNumSteps; ++i)
    s.can_open[i] = teach::CanOpen(facts, teach::kAllSteps[i]);
  s.current_step = step;
  s.next_step = teach::NextStep(facts);
  if (p >= 1) {
    s.devices = {
        {"camera", "simulated", "top camera, 64x64 RGB (MuJoCo, EGL)", true, 30.0, ""},
        {"arm", "simulated", "UR5 in MuJoCo, 10 Hz joint-velocity control", true, 10.0, ""},
        {"beacons", "simulated", "DWM1001 lec lines through the serial parser", true, 10.0, ""},
        {"teleop", "keyboard", "arrows move the arm", true, 0.0, ""},
        {"teleop", "gamepad", "none found", false, 0.0, ""}};
    s.connected_scanned = true;
    s.connected_where = "/dev";
    s.connected = {{"beacon", "/dev/ttyACM0", "SEGGER_J-Link_000760012345", true, "not probed"},
                   {"camera", "/dev/video0", "", true, "not probed"},
                   {"gamepad", "/dev/input/js0", "Xbox Wireless Controller", true, "not probed"}};
    s.safety.limits = "1 rad/s, 5 rad/s^2, tool floor 5 mm, watchdog 200 ms";
    s.safety.commands = 1214;
    s.safety.changed = 3;
    s.camera = SyntheticCamera();
    s.camera_frame = 1;
    s.objects = {{"plate", 110, 60, true}, {"bowl", 45, 35, true}, {"toast", 49, 86, true}};
    BeaconView beacon;
    beacon.name = "plate";
    beacon.object = p >= 2 ? "plate" : "";
    beacon.quantity = "position";
    beacon.unit = "m";
    beacon.reading = {0.609f, 0.468f};
    beacon.pixel = std::array<float, 2>{112, 58};
    beacon.rate_hz = 9.8;
    beacon.dropout_fraction = 0.02;
    beacon.noise_m = 0.07;
    s.beacons = {beacon};
  }
  if (p >= 3) {
    s.calibration.present = true;
    s.calibration.passed = true;
    s.calibration.rmse_m = 0.0292;
    s.calibration.p95_m = 0.0507;
    s.calibration.residual_m = {0.012, 0.030, 0.027, 0.024, 0.051, 0.031,
                                0.035, 0.024, 0.019, 0.023, 0.039, 0.006};
    s.calibration.inlier.assign(12, true);
  }
  s.teleop = TeleopMode::kScripted;
  s.teleop_choices = {{TeleopMode::kScripted, true, ""},
                      {TeleopMode::kKeyboard, true, ""},
                      {TeleopMode::kGamepad, false, "no gamepad connected"}};
  s.grip_m = {0.33f, 0.0f, 0.25f};
  s.grip = {GripState::kOpen, "toast", 0.005f, 0.011f};
  if (p >= 1) {
    // The teacher's 3-D view: the same synthetic table, the gripper over the toast.
    s.teacher_view.available = true;
    s.teacher_view.image = SyntheticCamera();
    s.teacher_view.frame = 1;
    s.teacher_view.azimuth_deg = 90;
    s.teacher_view.elevation_deg = -35;
    s.teacher_view.distance_m = 1.3f;
    s.teacher_view.grip_pixel = {49, 60};
    s.teacher_view.spot_pixel = {49, 86};
  }
  s.recent_sessions = {"/home/lab/sessions/toast", "/home/lab/sessions/cups"};
  if (p >= 4) {
    for (int i = 0; i < 4; ++i) {
      s.episodes.push_back(
          {"demo_" + std::to_string(i), 130 + 3 * i, 13.0 + 0.3 * i, true, i == 2, "train", ""});
    }
    s.teacher_seconds = 54.0 + 4.6 + 4.0;
    s.teacher_demo_seconds = 54.0;
    s.teacher_placement_seconds = 4.6;
    s.teacher_play_seconds = 4.0;
    s.play_samples = 40;
  }
  if (p >= 5) {
    for (const char* method : {"baseline", "recon"}) {
      TrainingView t;
      t.method = method;
      t.label = std::string(method) == "baseline" ? "Baseline" : "RECON (Play)";
      t.done = true;
      t.step = t.steps = 6001;
      t.seconds = std::string(method) == "baseline" ? 18.8 : 37.5;
      for (int k = 0; k < 60; ++k) {
        t.loss_step.push_back(100.0f * k);
        t.action_loss.push_back(10.0f * std::exp(-0.06f * k) - 9.0f + 0.3f * std::sin(1.7f * k));
        if (t.method == "recon") t.beacon_loss.push_back(3.0f * std::exp(-0.05f * k) - 2.0f);
      }
      s.training.push_back(t);
    }
  }
  if (p >= 6) {
    const auto rollout = [](const char* method, const char* label, double distance, double sem,
                            double success) {
      RolloutView r;
      r.method = method;
      r.label = label;
      r.metric_name = "final toast-to-plate distance (m)";
      r.metric_mean = distance;
      r.metric_sem = sem;
      r.has_success = true;
      r.success_rate = success;
      r.tests = 20;
      return r;
    };
    s.rollouts = {rollout("baseline", "Baseline", 0.407, 0.010, 0.0),
                  rollout("recon", "RECON (Play)", 0.375, 0.022, 0.05)};
    // The playback of test scene 3, step 42 of 201.
    for (RolloutView& r : s.rollouts) {
      r.has_replay = true;
      r.scenario = 2;
      r.frame = 42;
      r.frames = 201;
      r.scenario_seed = 1234567;
      r.scenario_metric = r.method == "baseline" ? 0.412 : 0.031;
      r.scenario_succeeded = r.method == "recon";
      r.scene_failures.assign(20, r.method == "recon" ? "" : "never picked the toast up");
      if (r.method == "baseline") r.scene_failures[2] = "delivered towards the bowl";
      r.frame_image = SyntheticCamera();
      r.frame_id = 1;
    }
    s.report_path = "sessions/toast/report/report.html";
  }
  s.status = facts.session_open ? "Session sessions/toast: tabletop, simulated cell." : "";
  return s;
}

}  // namespace recon::ui::testing
