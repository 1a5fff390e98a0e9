#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/calib/rigid_fit.h"
#include "engine/devices/arm.h"
#include "engine/devices/beacon_source.h"
#include "engine/devices/camera.h"
#include "engine/devices/clock.h"
#include "engine/worlds/world.h"

namespace recon::cell {

/// The newest frame of a camera, without waiting for one: what a control loop reads, so a slow
/// camera never holds up the arm. FrameGrabber (real_cell.h) is the real one.
class LatestFrameSource {
 public:
  virtual ~LatestFrameSource() = default;
  /// The newest frame, or nullptr before the first. UserError naming the camera when capture is
  /// failing (the camera is gone).
  virtual std::shared_ptr<const devices::CameraFrame> Latest() const = 0;
  virtual std::string Describe() const = 0;
};

/// How a RealCellWorld is configured.
struct RealCellWorldOptions {
  /// "none" (b empty) or "plate" (the plate beacon's table x, y: b has 2 entries), as Tabletop.
  std::string placement = "plate";
  /// y is the camera frame area-averaged to image_size x image_size (Tabletop's 64 by default).
  int image_size = 64;
  /// The UWB -> table fit of the cell's calibration (calib::CalibrationReport::transform:
  /// p_table = uwb_to_table.Apply(p_uwb)). Without it BeaconReading refuses ("calibrate first").
  std::optional<calib::RigidTransform> uwb_to_table;
  /// The name the beacon beside the plate has in the BeaconSource (the profile's names map).
  std::string plate_beacon = "plate";
  /// A beacon reading older than this is no reading: the beacon was unplugged or went silent.
  double beacon_max_age_s = 1.0;
  /// Names of the devices in error messages (e.g. "UR5 at 192.168.1.10"); empty: Describe().
  std::string camera_name, beacons_name, arm_name;
};

/// The tabletop task over a real cell's devices, with exactly Tabletop's shapes, so sessions,
/// training, the recorder and rollouts work unchanged on a real UR5:
/// x = the 6 joint angles minus Ur5Arm::kHome, then the gripper opening (7); y = the newest camera
/// frame area-averaged to S x S, channels first, 0-255 (3 S S); b = the plate beacon's table x, y
/// (2, placement "plate"); u = 6 joint velocities (rad/s) and the gripper (closes above 0.5),
/// sent to the arm (a GuardedArm: the safety envelope judges every command).
///
/// Time is real: Step returns 0.1 s (StepSeconds) after the previous Step on `clock`, the
/// paper's 10 Hz. The scene is the person's: Reset only stops the arm, there is no scripted
/// expert and no automatic score. A device that is gone or has not delivered yet makes
/// Observe, Step and BeaconReading throw UserError naming it.
class RealCellWorld : public worlds::World {
 public:
  static constexpr int kEpisodeLength = 200;
  static constexpr double kControlPeriod_s = 0.1;
  static constexpr int kPlayPerScenario = 10;

  /// The devices must outlive the world. Throws UserError for an unknown placement, an image
  /// size below 16 or a non-positive beacon age.
  RealCellWorld(const LatestFrameSource& camera, devices::BeaconSource& beacons, devices::Arm& arm,
                const devices::Clock& clock, RealCellWorldOptions options);

  std::string Name() const override { return "tabletop"; }
  DataSpec Spec() const override;
  int EpisodeLength() const override { return kEpisodeLength; }
  /// Stops the arm; the person sets the scene up. `seed` is unused: the scene is not drawn.
  void Reset(uint64_t seed) override;
  worlds::Observation Observe() const override;
  /// Sends u, then waits until kControlPeriod_s after the previous Step. std::invalid_argument
  /// for a size other than 7 (a programming error, as in Tabletop).
  void Step(const std::vector<float>& u) override;
  /// UserError: a real cell is taught by a person (keyboard or gamepad).
  std::vector<float> ExpertAction() const override;
  /// The plate beacon's newest reading mapped into the table frame (x, y); empty for "none".
  std::vector<float> BeaconReading() override;
  /// The current observation and beacon reading: the person moves the objects, the arm stays.
  PlaySample SamplePlay() override;
  int PlaySamplesPerScenario() const override { return kPlayPerScenario; }
  /// Not measured in a real cell: always 0.
  double EpisodeMetric() const override { return 0.0; }
  /// No metric (the teacher judges a trial), 10 Hz.
  worlds::WorldTraits Traits() const override;

  const RealCellWorldOptions& options() const { return options_; }

 private:
  std::string CameraName() const;
  std::string BeaconsName() const;
  std::string ArmName() const;

  const LatestFrameSource& camera_;
  devices::BeaconSource& beacons_;
  devices::Arm& arm_;
  const devices::Clock& clock_;
  RealCellWorldOptions options_;
  // The plate beacon's newest UWB position and when this world saw it (clock_ seconds): the
  // BeaconSource's own stamps need not be on clock_.
  std::optional<Eigen::Vector3d> plate_uwb_m_;
  double plate_seen_s_ = 0;
  std::optional<double> last_step_s_;  // none after Reset: the first step does not wait
};

/// Resizes `image` to size x size by area averaging (each output pixel is the mean of the input
/// area it covers, partial pixels weighted, rounded to the nearest level) and lays it out as
/// Tabletop's y: channels first, whole 0-255 values (a session stores images as 8 bits).
std::vector<float> AreaAveragedChannelsFirst(const RgbImage& image, int size);

}  // namespace recon::cell
