#include "engine/worlds/guarded_ur5.h"

namespace recon::worlds {

GuardedUr5::GuardedUr5(Ur5Arm& arm, double control_period_s, const safety::SafetyLimits& limits)
    : device_(arm, clock_), guard_(device_, limits, clock_), period_s_(control_period_s) {
  guard_.SetCommandPeriod(control_period_s);  // validates the period
}

void GuardedUr5::BeforePeriod() {
  guard_.CheckWatchdog();
  device_.CheckWatchdog();
}

}  // namespace recon::worlds
