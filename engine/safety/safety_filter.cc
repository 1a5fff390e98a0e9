#include "engine/safety/safety_filter.h"

#include <utility>

namespace recon::safety {

SafetyFilter::SafetyFilter(SafetyLimits limits) : envelope_(std::move(limits)) {}

const SafetyDecision& SafetyFilter::Apply(const JointVector& q_rad,
                                          const JointVector& requested_rad_s, double dt_s) {
  ++stats_.commands;
  last_decision_ = envelope_.Filter(q_rad, in_force_rad_s_, requested_rad_s, dt_s);
  Count(last_decision_.reasons);
  in_force_rad_s_ = last_decision_.command_rad_s;
  return last_decision_;
}

void SafetyFilter::CountStop(uint32_t reasons) {
  ++stats_.commands;
  last_decision_ = SafetyDecision{};
  last_decision_.reasons = reasons;
  Count(reasons);
  in_force_rad_s_ = {};
}

void SafetyFilter::Count(uint32_t reasons) {
  if (reasons == kNone) return;
  ++stats_.changed;
  if (reasons & kNonFinite) ++stats_.non_finite;
  if (reasons & kVelocity) ++stats_.velocity;
  if (reasons & kAcceleration) ++stats_.acceleration;
  if (reasons & kPositionLimit) ++stats_.position_limit;
  if (reasons & kToolFloor) ++stats_.tool_floor;
  if (reasons & kEmergencyStop) ++stats_.emergency_stop;
}

}  // namespace recon::safety
