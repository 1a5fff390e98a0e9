// The tabletop's replay: the pose a camera image shows, kept for every step of a rollout and
// set again to draw that step later (the studio's rollout playback).

#include <mujoco/mujoco.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/worlds/tabletop.h"

namespace recon::worlds {

int Tabletop::ReplayStateSize() const {
  const mjModel* m = scene_.model();
  return m->nq + 7 * m->nmocap;
}

std::vector<double> Tabletop::ReplayState() const {
  const mjModel* m = scene_.model();
  const mjData* d = scene_.data();
  std::vector<double> state(static_cast<size_t>(ReplayStateSize()));
  // mj_step computes positions (which the camera image and the metrics read) before it
  // integrates, so after a Step qpos is one physics substep ahead of the frame. Integrating back
  // with the velocity that substep used recovers the pose drawn, so a replayed frame is the one
  // the policy saw, not one 2 ms later. After a Reset qvel is 0 and this is qpos itself.
  mju_copy(state.data(), d->qpos, m->nq);
  mj_integratePos(m, state.data(), d->qvel, -m->opt.timestep);
  mju_copy(state.data() + m->nq, d->mocap_pos, 3 * m->nmocap);
  mju_copy(state.data() + m->nq + 3 * m->nmocap, d->mocap_quat, 4 * m->nmocap);
  return state;
}

void Tabletop::ShowReplayState(const std::vector<double>& state) {
  const int expected = ReplayStateSize();
  if (static_cast<int>(state.size()) != expected) {
    throw UserError("a tabletop replay state has " + std::to_string(expected) +
                    " values (qpos and mocap poses of this scene), got " +
                    std::to_string(state.size()));
  }
  for (size_t i = 0; i < state.size(); ++i) {
    if (!std::isfinite(state[i])) {
      throw UserError("tabletop replay state value " + std::to_string(i) + " is not finite");
    }
  }
  const mjModel* m = scene_.model();
  mjData* d = scene_.data();
  mju_copy(d->qpos, state.data(), m->nq);
  mju_copy(d->mocap_pos, state.data() + m->nq, 3 * m->nmocap);
  mju_copy(d->mocap_quat, state.data() + m->nq + 3 * m->nmocap, 4 * m->nmocap);
  // At rest: ReplayState() then gives back exactly `state` (it integrates back by qvel).
  mju_zero(d->qvel, m->nv);
  mj_forward(m, d);
  plate_side_ = PlatePosition().y() >= 0 ? 1 : -1;
  Render();
}

}  // namespace recon::worlds
