#include "engine/teach/take_words.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/pauses.h"
#include "engine/worlds/outcome_words.h"

namespace recon::teach {

double LongestStillSeconds(const Episode& take, const std::vector<float>& motion, double step_s) {
  int longest = 0, run = 0;
  for (size_t t = 0; t < take.samples.size(); ++t) {
    run = IsPause(take, t, motion) ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest * step_s;
}

std::string TakeWords(const worlds::World& world, const Episode& take, bool done) {
  const std::map<std::string, double> details = world.OutcomeDetails();
  std::vector<std::string> parts;
  if (!done) {
    const std::string failure = worlds::DescribeFailure(details, false);
    if (!failure.empty()) parts.push_back("it " + failure);
  }
  const auto grasps = details.find("grasps");
  if (grasps != details.end() && grasps->second >= 2) {
    parts.push_back("the toast was picked up " +
                    std::to_string(static_cast<int>(std::lround(grasps->second))) + " times");
  }
  const double still_s = LongestStillSeconds(take, world.ActionNoiseScale(), world.StepSeconds());
  if (still_s >= kLongStillSeconds) {
    char text[64];
    std::snprintf(text, sizeof text, "the arm stood still for %.1f s", still_s);
    parts.push_back(text);
  }
  std::string words;
  for (const std::string& part : parts) words += (words.empty() ? "" : "; ") + part;
  return words;
}

}  // namespace recon::teach
