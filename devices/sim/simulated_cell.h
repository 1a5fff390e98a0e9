#pragma once

#include <cstdint>
#include <memory>

#include "devices/sim/simulated_beacon_source.h"
#include "devices/sim/simulated_camera.h"
#include "engine/calib/rigid_fit.h"
#include "engine/devices/clock.h"
#include "engine/devices/teleop.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/tabletop.h"

namespace recon::sim {

/// How the simulated cell is set up.
struct SimulatedCellOptions {
  worlds::TabletopOptions tabletop;
  /// The installation: the hidden table -> UWB frame and the beacon's noise stream. Scenarios are
  /// drawn by Reset(seed), independently of it.
  uint64_t seed = 1;
};

/// The simulated teaching cell behind the device interfaces: the tabletop world, its simulated
/// time, the top camera, the plate's UWB beacon and the world's guarded arm (the simulated UR5
/// behind the safety envelope, watchdog and e-stop, as a real cell's).
///
/// Time moves only in Step/Advance, by one control period (0.1 s) each, so capturing the camera
/// and polling the beacons once per step gives 10 Hz streams. The devices keep running across
/// Reset (clock, frame numbers and the beacon's noise continue, as in a real cell); a run is
/// reproduced by the cell seed plus the same sequence of Reset seeds and commands.
///
/// The plate beacon streams whatever the world's placement: it stands in the scene either way,
/// and whether a recording uses it is the recorder's choice. Bound to the thread that made it
/// (its renderers are). Not copyable or movable: the devices refer to its parts.
class SimulatedCell {
 public:
  static constexpr char kCamera[] = "top";
  static constexpr char kBeaconName[] = "plate";
  static constexpr char kBeaconSite[] = "beacon";

  /// Makes two renderers with `renderer_factory` (the world's and the camera's). UserError for
  /// bad options or when no renderer can be made.
  SimulatedCell(const SimulatedCellOptions& options,
                const worlds::SceneRendererFactory& renderer_factory);
  SimulatedCell(const SimulatedCell&) = delete;
  SimulatedCell& operator=(const SimulatedCell&) = delete;

  /// Draws a new scenario (Tabletop::Reset) with the arm at home and stopped.
  void Reset(uint64_t seed);
  /// Applies `command` to the arm, then Advance(). `finished` is the recorder's business.
  void Step(const devices::TeleopCommand& command);
  /// One control period under the arm's current command (Tabletop::Advance): the watchdogs are
  /// checked, the world steps its physics, the clock moves on 0.1 s.
  void Advance() { world_->Advance(); }

  worlds::Tabletop& world() { return *world_; }
  const devices::ManualClock& clock() const { return world_->clock(); }
  SimulatedCamera& camera() { return *camera_; }
  SimulatedBeaconSource& beacons() { return *beacons_; }
  safety::GuardedArm& arm() { return world_->guarded_arm(); }
  /// The installation's hidden pose: p_uwb = hidden_table_to_uwb().Apply(p_table).
  const calib::RigidTransform& hidden_table_to_uwb() const { return hidden_table_to_uwb_; }

 private:
  calib::RigidTransform hidden_table_to_uwb_;
  std::unique_ptr<worlds::Tabletop> world_;
  std::unique_ptr<SimulatedCamera> camera_;
  std::unique_ptr<SimulatedBeaconSource> beacons_;
};

}  // namespace recon::sim
