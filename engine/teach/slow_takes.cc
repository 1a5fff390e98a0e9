#include "engine/teach/slow_takes.h"

#include <algorithm>
#include <cstdio>

namespace recon::teach {

namespace {

/// The median length of every kept take but take `skip`.
double MedianOfOthers(const std::vector<KeptTake>& takes, size_t skip) {
  std::vector<int64_t> others;
  for (size_t i = 0; i < takes.size(); ++i) {
    if (i != skip) others.push_back(takes[i].samples);
  }
  std::sort(others.begin(), others.end());
  const size_t n = others.size();
  return n % 2 == 1 ? static_cast<double>(others[n / 2])
                    : 0.5 * static_cast<double>(others[n / 2 - 1] + others[n / 2]);
}

}  // namespace

std::vector<size_t> SlowTakes(const std::vector<KeptTake>& takes) {
  std::vector<size_t> slow;
  if (takes.size() < 2) return slow;
  for (size_t i = 0; i < takes.size(); ++i) {
    const double others = MedianOfOthers(takes, i);
    if (others > 0 && static_cast<double>(takes[i].samples) > kSlowTakeFactor * others) {
      slow.push_back(i);
    }
  }
  return slow;
}

std::string SlowTakesWarning(const std::vector<KeptTake>& takes, double step_s) {
  const std::vector<size_t> slow = SlowTakes(takes);
  if (slow.empty()) return "";
  std::string list;
  for (size_t i : slow) {
    const double others = MedianOfOthers(takes, i);
    char part[160];
    std::snprintf(part, sizeof(part), "%s took %.1f s, %.1f times the others' %.1f s",
                  takes[i].name.c_str(), static_cast<double>(takes[i].samples) * step_s,
                  static_cast<double>(takes[i].samples) / others, others * step_s);
    list += (list.empty() ? "" : "; ") + std::string(part);
  }
  const bool one = slow.size() == 1;
  return std::string(one ? "A slow take: " : "Slow takes: ") + list +
         " (median). A policy learns the pace with the route, and rollouts are given 1.5 times "
         "the longest take: re-record " +
         (one ? "it" : "them") + " or mark " + (one ? "it" : "them") +
         " Bad if the task was not done as it should be.";
}

}  // namespace recon::teach
