#pragma once

#include <string>

#include "engine/devices/teleop.h"
#include "engine/worlds/world.h"

namespace recon::sim {

/// The simulated teacher: a world's scripted expert as a devices::Teleop. For a world whose
/// actions are 6 joint velocities (rad/s) and a gripper value (close when > 0.5), as the
/// tabletop's are, each Poll turns ExpertAction() in the world's current state into a command.
/// The first EpisodeLength() polls after construction or Restart() carry the expert's actions;
/// every poll after that is a zero-motion command with `finished` set (the demonstration is over).
///
/// Holds the world by reference; its owner keeps it alive.
class ScriptedTeleop final : public devices::Teleop {
 public:
  explicit ScriptedTeleop(worlds::World& world);

  /// UserError when the world's expert does not give 7 values (not a 6-joint arm world).
  devices::TeleopCommand Poll() override;
  /// E.g. "scripted expert of tabletop".
  std::string Describe() const override;

  /// Starts a new demonstration (after the world's Reset).
  void Restart() { polls_ = 0; }
  int polls() const { return polls_; }

 private:
  worlds::World& world_;
  int polls_ = 0;
};

}  // namespace recon::sim
