#include "app/studio/simulated_cell_source.h"

#include "app/cli/session_world.h"
#include "app/studio/cell_view.h"
#include "engine/core/error.h"
#include "engine/worlds/world_factory.h"

namespace recon::studio {

namespace {

// The studio opens tabletop sessions only (StudioCell::OpenSessionAt checks the manifest before
// it makes a world), so this names a defect, not a user's mistake.
worlds::Tabletop& TabletopOf(worlds::World& world) {
  auto* tabletop = dynamic_cast<worlds::Tabletop*>(&world);
  if (tabletop == nullptr) throw std::logic_error("the studio's simulated cell is the tabletop");
  return *tabletop;
}

const worlds::Tabletop& TabletopOf(const worlds::World& world) {
  return TabletopOf(const_cast<worlds::World&>(world));
}

}  // namespace

SimulatedCellSource::SimulatedCellSource(worlds::SceneRenderer& renderer) : renderer_(renderer) {}

double SimulatedCellSource::DefaultBeaconNoise(const std::string& world) const {
  return worlds::DefaultBeaconNoise(world);
}

double SimulatedCellSource::DefaultDemoNoise(const std::string& world) const {
  return worlds::DefaultDemoNoise(world);
}

std::unique_ptr<worlds::World> SimulatedCellSource::MakeNewWorld(const teach::SessionSetup& setup) {
  return cli::MakeSetupWorld(setup);
}

std::unique_ptr<worlds::World> SimulatedCellSource::MakeSessionWorld(
    const store::Session& session) {
  const store::SessionManifest& m = session.manifest();
  return cli::MakeSessionWorld(m, m.placement);
}

Eigen::Vector3d SimulatedCellSource::TeleopVelocity(worlds::World&, const ui::TeleopInput& input,
                                                    ViewSize,
                                                    const worlds::OrbitCamera& teacher_view,
                                                    double speed_m_s) const {
  return studio::TeleopVelocity(teacher_view, input, speed_m_s);
}

std::optional<std::vector<float>> SimulatedCellSource::IdleBeaconReading(worlds::World& world,
                                                                         const store::Session&) {
  return world.BeaconReading();
}

bool SimulatedCellSource::ShowLive(worlds::World& world, const store::Session& session,
                                   const std::vector<float>& reading, bool wanted, ViewSize view,
                                   ui::StudioSnapshot& s) {
  if (!wanted) return false;
  ShowTabletopView(TabletopOf(world), renderer_, view.width, view.height, session.manifest(),
                   reading, s);
  s.camera_frame = ++frames_;
  return true;
}

bool SimulatedCellSource::ShowTeacherView(worlds::World& world, const worlds::OrbitCamera& camera,
                                          ViewSize view, ui::StudioSnapshot& s) {
  studio::ShowTeacherView(TabletopOf(world), renderer_, camera, view.width, view.height, s);
  s.teacher_view.frame = ++teacher_frames_;
  return true;
}

void SimulatedCellSource::ShowArm(const worlds::World& world, ui::StudioSnapshot& s) const {
  const worlds::Tabletop& tabletop = TabletopOf(world);
  s.grip = GripViewOf(tabletop);
  const Eigen::Vector3d grip = tabletop.arm().GripPosition();
  s.grip_m = {static_cast<float>(grip.x()), static_cast<float>(grip.y()),
              static_cast<float>(grip.z())};
  s.gripper_closed = tabletop.arm().GripperClosed();
}

safety::GuardedArm* SimulatedCellSource::GuardedArmOf(worlds::World* world) const {
  return world == nullptr ? nullptr : &TabletopOf(*world).guarded_arm();
}

}  // namespace recon::studio
