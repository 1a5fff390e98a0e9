#pragma once

#include <vector>

namespace recon {

double Mean(const std::vector<double>& values);
/// Standard error of the mean: sample standard deviation / sqrt(n); 0 for n < 2.
double StandardError(const std::vector<double>& values);

}  // namespace recon
