#include "engine/teach/teacher_mix.h"

#include <algorithm>
#include <cstddef>
#include <map>

namespace recon::teach {

namespace {

/// A source as a teacher would name it.
std::string TeacherName(const std::string& source) {
  if (source == "scripted-teleop") return "the scripted teacher";
  if (source == "keyboard-teleop") return "the keyboard";
  if (source == "gamepad-teleop") return "the gamepad";
  return source.empty() ? "an unnamed source" : source;
}

}  // namespace

std::string TeacherMixWarning(const std::vector<std::string>& sources) {
  std::map<std::string, int> counts;
  for (const std::string& source : sources) ++counts[source];
  if (counts.size() < 2) return "";
  std::string parts;
  for (const auto& [source, count] : counts) {
    parts += (parts.empty() ? "" : ", ") + std::to_string(count) + " by " + TeacherName(source);
  }
  return "The demonstrations come from " + std::to_string(counts.size()) + " teachers (" + parts +
         "): a policy learns best from one teacher's style. Mark the others Bad or re-record "
         "them with one teleop.";
}

bool IsAPersonsTake(const std::string& source) { return source != "scripted-teleop"; }

bool MostlyAPersonsTakes(const std::vector<bool>& person) {
  const auto persons = std::count(person.begin(), person.end(), true);
  return 2 * persons > static_cast<std::ptrdiff_t>(person.size());
}

}  // namespace recon::teach
