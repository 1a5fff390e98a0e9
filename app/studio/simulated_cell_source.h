#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/studio/cell_source.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/tabletop.h"

namespace recon::studio {

/// The simulated tabletop cell (the studio's default): the MuJoCo world draws its own camera
/// view, its beacons read where the world puts them (with the session's noise), the scripted
/// teacher can demonstrate, and the world's UR5 stands behind its guard (worlds::GuardedUr5) as
/// a real one does.
class SimulatedCellSource final : public CellSource {
 public:
  /// `renderer` draws the live view (made on the cell thread, which owns its GL context); it
  /// must outlive the source.
  explicit SimulatedCellSource(worlds::SceneRenderer& renderer);

  std::string Kind() const override { return "simulated"; }
  double DefaultBeaconNoise(const std::string& world) const override;
  double DefaultDemoNoise(const std::string& world) const override;
  std::unique_ptr<worlds::World> MakeNewWorld(const teach::SessionSetup& setup) override;
  void DescribeInto(store::SessionManifest&) const override {}
  std::unique_ptr<worlds::World> MakeSessionWorld(const store::Session& session) override;

  std::optional<std::string> FixedBeaconObject() const override { return "plate"; }
  bool HasScriptedTeacher() const override { return true; }
  Eigen::Vector3d TeleopVelocity(worlds::World& world, const ui::TeleopInput& input, ViewSize view,
                                 const worlds::OrbitCamera& teacher_view,
                                 double speed_m_s) const override;
  std::string PlaySource() const override { return "simulated-play"; }

  std::optional<std::vector<float>> IdleBeaconReading(worlds::World& world,
                                                      const store::Session& session) override;
  bool ShowLive(worlds::World& world, const store::Session& session,
                const std::vector<float>& reading, bool wanted, ViewSize view,
                ui::StudioSnapshot& s) override;
  bool ShowTeacherView(worlds::World& world, const worlds::OrbitCamera& camera, ViewSize view,
                       ui::StudioSnapshot& s) override;
  void ShowArm(const worlds::World& world, ui::StudioSnapshot& s) const override;
  void ShowDevices(ui::StudioSnapshot&) const override {}
  safety::GuardedArm* GuardedArmOf(worlds::World* world) const override;

 private:
  worlds::SceneRenderer& renderer_;
  uint64_t frames_ = 0;          ///< live frames rendered so far
  uint64_t teacher_frames_ = 0;  ///< and teacher's views
};

}  // namespace recon::studio
