#pragma once

#include <string>

namespace recon {

/// The CPU's model name as the kernel reports it (the first "model name" line of
/// /proc/cpuinfo), or "unknown" where there is none. Results of chaotic computations such as
/// training differ between CPUs, so outputs that depend on them name the CPU they came from.
std::string CpuModelName();

}  // namespace recon
