#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/dataset.h"

namespace recon {

/// A person teaching stops to look and think, and waits for what they did to show: samples in
/// which the teacher's command moves nothing and changes nothing (every motion entry of the
/// action zero, every other entry, e.g. a gripper command, as in the sample before). Learnt, such
/// a sample says "in this state, do nothing", and the next state is the same state: a place the
/// robot can stay in for ever, which is how a policy taught by a person hovers beside the toast
/// or over the plate without closing or letting go. The field's name for them is no-op (idle)
/// actions.
///
/// `motion` marks the action's motion entries (non-zero: joint velocities; zero: discrete
/// commands such as the gripper), as World::ActionNoiseScale gives it; empty means every entry is
/// motion.
bool IsPause(const Episode& episode, size_t t, const std::vector<float>& motion);

/// The dataset with the pauses of its demonstrations left out (play data unchanged); a
/// demonstration that is nothing but pauses keeps its first sample. `of`, when not empty, says
/// per demonstration whether its pauses go (a person's takes) or it is kept whole (a scripted
/// teacher's, whose commands that move nothing are deliberate waits, e.g. for the fingers).
/// `dropped`, when given, receives how many samples went.
Dataset WithoutPauses(const Dataset& dataset, const std::vector<float>& motion,
                      int64_t* dropped = nullptr, const std::vector<bool>& of = {});

}  // namespace recon
