#pragma once

namespace recon {

/// Stops glibc from returning large activation buffers to the OS after every training step and
/// faulting them back in on the next (STACK.md measured 3.5x on a small CNN). Call once at
/// start-up of any process that trains.
void TuneMallocForTraining();

}  // namespace recon
