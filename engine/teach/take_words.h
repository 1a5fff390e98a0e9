#pragma once

#include <string>

#include "engine/core/dataset.h"
#include "engine/worlds/world.h"

namespace recon::teach {

/// How long a stretch of standing still makes a take worth a word: a person looking for 5 s is
/// thinking; 10 s is a take left alone.
inline constexpr double kLongStillSeconds = 5.0;

/// The longest run of samples in `take` in which the teacher's command moved nothing (IsPause),
/// in seconds of `step_s` each; `motion` as IsPause takes it.
double LongestStillSeconds(const Episode& take, const std::vector<float>& motion, double step_s);

/// What a teacher is told about a person's take as it ends, in their words, from the world as it
/// ended and the take's samples; "" when there is nothing to say. For a take that is not done:
/// what became of the object (worlds::DescribeFailure: "dropped the toast off the table", "let
/// the toast go off the plate, 14 cm from its middle"). For any take: a regrasp ("the toast was
/// picked up 3 times") and a long stillness ("the arm stood still for 10.0 s").
std::string TakeWords(const worlds::World& world, const Episode& take, bool done);

}  // namespace recon::teach
