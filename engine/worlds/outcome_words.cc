#include "engine/worlds/outcome_words.h"

#include <cmath>

namespace recon::worlds {

namespace {

bool Flag(const std::map<std::string, double>& details, const std::string& key) {
  const auto it = details.find(key);
  return it != details.end() && it->second > 0;
}

}  // namespace

std::string DescribeFailure(const std::map<std::string, double>& details, bool succeeded) {
  if (succeeded || details.count("grasped") == 0) return "";
  // In the order a rollout goes: the grasp, the carry, the release.
  if (!Flag(details, "grasped")) {
    return Flag(details, "closes_on_nothing")
               ? "closed the gripper on nothing, never held the toast"
               : "never picked the toast up";
  }
  if (Flag(details, "toast_held")) return "kept holding the toast to the end";
  if (Flag(details, "toast_off_table")) return "dropped the toast off the table";
  if (Flag(details, "grip_nearer_bowl")) return "delivered towards the bowl";
  const auto to_plate = details.find("toast_to_plate_m");
  if (to_plate == details.end()) return "let the toast go off the plate";
  return "let the toast go off the plate, " +
         std::to_string(static_cast<int>(std::lround(to_plate->second * 100))) +
         " cm from its middle";
}

}  // namespace recon::worlds
