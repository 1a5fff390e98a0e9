#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/safety/guarded_arm.h"
#include "engine/store/session.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/teach/recorder.h"
#include "engine/teach/session_setup.h"
#include "engine/worlds/orbit_camera.h"
#include "engine/worlds/world.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The live view's size in pixels (the Record screen's camera, where teleop input is given).
struct ViewSize {
  int width = 320;
  int height = 240;
};

/// Where the studio's cell comes from: the simulated tabletop (a MuJoCo world with its own
/// camera, beacons and scripted teacher) or a real cell's devices (camera, beacons, UR5). The
/// studio's controller talks to the cell only through this, so every screen and command has one
/// code path for both; what differs lives in the two implementations. Cell thread only.
class CellSource {
 public:
  virtual ~CellSource() = default;

  /// The manifest's `cell` of the sessions this source teaches: "simulated" or "real".
  virtual std::string Kind() const = 0;

  /// A new session's defaults where the teacher gave none: the beacons' noise (simulated
  /// beacons carry a DWM1001's, real ones bring their own) and the demonstration noise (a real
  /// arm is only perturbed when asked).
  virtual double DefaultBeaconNoise(const std::string& world) const = 0;
  virtual double DefaultDemoNoise(const std::string& world) const = 0;
  /// The world of a new session made from `setup`, and what its manifest records of the cell.
  virtual std::unique_ptr<worlds::World> MakeNewWorld(const teach::SessionSetup& setup) = 0;
  virtual void DescribeInto(store::SessionManifest& manifest) const = 0;
  /// The world of an opened session (with its calibration, where the cell needs one).
  virtual std::unique_ptr<worlds::World> MakeSessionWorld(const store::Session& session) = 0;

  /// Whether the scripted teacher can demonstrate here (the simulated cell only).
  virtual bool HasScriptedTeacher() const = 0;
  /// The grip point's table velocity for a teleop input, `speed_m_s` at full deflection: the
  /// arrows move the arm the way the teacher sees it move on screen, in the teacher's 3-D view
  /// (`teacher_view`) where the cell has one, else in the live camera view (`view`).
  virtual Eigen::Vector3d TeleopVelocity(worlds::World& world, const ui::TeleopInput& input,
                                         ViewSize view, const worlds::OrbitCamera& teacher_view,
                                         double speed_m_s) const = 0;
  /// How play samples record who moved the objects ("simulated-play", "person-play").
  virtual std::string PlaySource() const = 0;

  /// The plate beacon's reading while nothing records (the Beacons screen's live value): in the
  /// table frame once the session is calibrated, in the beacons' own frame before (a real cell
  /// cannot map it yet). Nothing when no new reading arrived: the last one stands.
  virtual std::optional<std::vector<float>> IdleBeaconReading(worlds::World& world,
                                                              const store::Session& session) = 0;

  /// Fills the live camera, the objects one can assign a beacon to and the beacons drawn where
  /// `reading` puts them. `wanted` says whether a screen showing the camera is open (the
  /// simulated cell renders only then, so training gets the CPU). True when a frame was shown;
  /// its number (s.camera_frame) grows with every new frame.
  virtual bool ShowLive(worlds::World& world, const store::Session& session,
                        const std::vector<float>& reading, bool wanted, ViewSize view,
                        ui::StudioSnapshot& s) = 0;
  /// The teacher's 3-D view from `camera` at `view` pixels (ui::TeacherView); false, drawing
  /// nothing, where the cell has none (a real cell).
  virtual bool ShowTeacherView(worlds::World& world, const worlds::OrbitCamera& camera,
                               ViewSize view, ui::StudioSnapshot& s) = 0;
  /// The grip point, the gripper and what it holds, for the readout.
  virtual void ShowArm(const worlds::World& world, ui::StudioSnapshot& s) const = 0;
  /// The cell's device rows (a real cell's live status); the simulated cell's come from the
  /// session's manifest.
  virtual void ShowDevices(ui::StudioSnapshot& s) const = 0;
  /// The cell's arm behind its guard (the safety envelope, the watchdog and the e-stop): the
  /// simulated UR5 of `world` (the session's; null before one is open, and then so is this), or
  /// a real cell's UR5 whether a session is open or not. The studio teleoperates it, stops it
  /// and shows what the envelope did through this one mechanism for both. Null where the cell
  /// has no arm. Any thread may use the guard (it is thread-safe); the pointer itself is valid
  /// while `world` and the source are.
  virtual safety::GuardedArm* GuardedArmOf(worlds::World* world) const = 0;

  /// Whether the teacher paces the calibration, moving the beacon place by place (a real cell,
  /// cell::GuidedCalibration), rather than the cell running it by itself as a job (the
  /// simulated cell's scripted teacher).
  virtual bool GuidesCalibration() const { return false; }
  /// Where a beacon is fixed and cannot be moved by the teacher (the simulated tabletop's stands
  /// beside the plate), or nullopt where the teacher sticks it on whatever they mark (a real
  /// cell: the readings come from where it is, the label is the teacher's word).
  virtual std::optional<std::string> FixedBeaconObject() const { return std::nullopt; }
  /// Starts a guided calibration of `points` places; UserError when it cannot run here now.
  virtual void StartGuidedCalibration(int /*points*/) {
    throw UserError("this cell calibrates by itself");
  }
  /// One pass of the guided calibration: reads the camera and the beacons (nothing else reads
  /// the beacons meanwhile), fills `view`'s live fields and returns the fit once every place
  /// is taken (then the run is over). UserError when the fit cannot be made.
  virtual std::optional<calib::CalibrationReport> StepGuidedCalibration(
      ui::GuidedCalibrationView&) {
    return std::nullopt;
  }
  virtual void StopGuidedCalibration() {}
  /// Whether trained policies can be tried on a real arm here (StartTrials): a real cell's.
  virtual bool RunsTrials() const { return false; }
  /// Where the live camera sees the table point `p` (table frame), where the cell knows.
  virtual std::optional<std::array<float, 2>> TablePixel(const Eigen::Vector3d& /*p*/) const {
    return std::nullopt;
  }
};

}  // namespace recon::studio
