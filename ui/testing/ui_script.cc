#include "ui/testing/ui_script.h"

#include <imgui.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/number_check.h"
#include "ui/platform/frame_input.h"

namespace recon::ui {

namespace {

constexpr const char* kVerbs =
    "click, type, press, hold, wait, sleep, wait-idle, keyboard-take, person-takes, screenshot";

// A number of a script line, checked as a command-line option's is (engine/core/number_check).
double ParseNumber(const std::string& text, const std::string& what, double lo, double hi,
                   bool whole, bool above_lo) {
  const std::string problem = CheckNumber(text, lo, hi, whole, above_lo);
  if (!problem.empty()) throw UserError(what + ": " + problem);
  return std::strtod(text.c_str(), nullptr);
}

double ParseSeconds(const std::string& text, const std::string& verb) {
  return ParseNumber(text, verb + "'s seconds", 0.0, kMaxScriptSeconds, false, true);
}

int ParseKey(const std::string& name) {
  const int key = ScriptKeyNamed(name);
  if (key < 0) {
    throw UserError("unknown key '" + name +
                    "' (enter, tab, escape, backspace, delete, insert, home, end, space, up, "
                    "down, left, right, pageup, pagedown, f12; return, esc, pgup, pgdn and "
                    "arrowup-style names too, in any case)");
  }
  return key;
}

/// A screenshot's name: a relative path that stays inside the screenshot folder.
std::string CheckScreenshotName(const std::string& name) {
  if (name.empty()) throw UserError("screenshot needs a file name: screenshot <name>.png");
  const std::filesystem::path path(name);
  if (path.is_absolute() || path.has_root_name() || path.has_root_directory()) {
    throw UserError("screenshot '" + name +
                    "' is an absolute path; name a file inside the screenshot folder "
                    "(--screenshots)");
  }
  for (const std::filesystem::path& part : path) {
    if (part == "..") {
      throw UserError("screenshot '" + name + "' climbs out of the screenshot folder with '..'");
    }
  }
  const std::string extension = path.extension().string();
  if (extension != ".png" && extension != ".PNG") {
    throw UserError("screenshot '" + name + "' must end in .png (it is written as a PNG)");
  }
  return name;
}

ScriptStep ParseStep(const std::string& verb, const std::string& argument) {
  ScriptStep step;
  if (verb == "click" || verb == "type") {
    step.verb = verb == "click" ? ScriptStep::Verb::kClick : ScriptStep::Verb::kType;
    if (step.verb == ScriptStep::Verb::kClick && argument.empty()) {
      throw UserError("click needs a widget's label: click <label>");
    }
    step.text = argument;
  } else if (verb == "press") {
    step.verb = ScriptStep::Verb::kPress;
    step.key = ParseKey(argument);
  } else if (verb == "hold") {
    // hold <key> <seconds>: a key held down, e.g. an arrow driving the arm.
    step.verb = ScriptStep::Verb::kHold;
    const size_t gap = argument.find(' ');
    step.key = ParseKey(argument.substr(0, gap));
    if (gap == std::string::npos) throw UserError("hold needs seconds: hold <key> <seconds>");
    step.seconds = ParseSeconds(argument.substr(gap + 1), "hold");
  } else if (verb == "sleep") {
    // sleep <seconds>: frames at about 30 a second for that much wall time, e.g. to let a
    // playback or a teleop run as long as a person would watch it.
    step.verb = ScriptStep::Verb::kSleep;
    step.seconds = ParseSeconds(argument, "sleep");
  } else if (verb == "wait") {
    step.verb = ScriptStep::Verb::kWait;
    step.frames =
        static_cast<int>(ParseNumber(argument, "wait's frames", 0, kMaxScriptFrames, true, false));
  } else if (verb == "wait-idle") {
    step.verb = ScriptStep::Verb::kWaitIdle;
    step.seconds = argument.empty() ? 600.0 : ParseSeconds(argument, "wait-idle");
  } else if (verb == "keyboard-take") {
    // keyboard-take [seconds]: the scripted person (KeyboardPerson) gives the keyboard take that
    // has just been started, from what the Record screen shows.
    step.verb = ScriptStep::Verb::kKeyboardTake;
    step.seconds = argument.empty() ? 90.0 : ParseSeconds(argument, "keyboard-take");
  } else if (verb == "person-takes") {
    // person-takes N SEED: the realistic person (PersonPace::Realistic) records N demonstrations
    // in which the task is done, discarding and recording again a take that is not, as a person
    // at the keys does (UiDriver::PersonTakes).
    step.verb = ScriptStep::Verb::kPersonTakes;
    std::istringstream words(argument);
    std::string demos, seed, extra;
    words >> demos >> seed >> extra;
    if (seed.empty() || !extra.empty()) {
      throw UserError("person-takes needs two numbers: the demonstrations to keep and a seed");
    }
    step.frames =
        static_cast<int>(ParseNumber(demos, "person-takes' demonstrations", 1, 100, true, false));
    step.seed = static_cast<uint64_t>(
        ParseNumber(seed, "person-takes' seed", 0, 4294967295.0, true, false));
  } else if (verb == "screenshot") {
    step.verb = ScriptStep::Verb::kScreenshot;
    step.text = CheckScreenshotName(argument);
  } else {
    throw UserError("unknown command '" + verb + "' (" + kVerbs + ")");
  }
  return step;
}

}  // namespace

int ScriptKeyNamed(const std::string& name) {
  // The names people write for these keys (xdotool's, browsers', keyboards'), in any case.
  static const std::pair<const char*, int> kNames[] = {
      {"enter", ImGuiKey_Enter},
      {"return", ImGuiKey_Enter},
      {"kp_enter", ImGuiKey_KeyPadEnter},
      {"kpenter", ImGuiKey_KeyPadEnter},
      {"tab", ImGuiKey_Tab},
      {"escape", ImGuiKey_Escape},
      {"esc", ImGuiKey_Escape},
      {"backspace", ImGuiKey_Backspace},
      {"delete", ImGuiKey_Delete},
      {"del", ImGuiKey_Delete},
      {"insert", ImGuiKey_Insert},
      {"home", ImGuiKey_Home},
      {"end", ImGuiKey_End},
      {"space", ImGuiKey_Space},
      {"spacebar", ImGuiKey_Space},
      {"up", ImGuiKey_UpArrow},
      {"arrowup", ImGuiKey_UpArrow},
      {"down", ImGuiKey_DownArrow},
      {"arrowdown", ImGuiKey_DownArrow},
      {"left", ImGuiKey_LeftArrow},
      {"arrowleft", ImGuiKey_LeftArrow},
      {"right", ImGuiKey_RightArrow},
      {"arrowright", ImGuiKey_RightArrow},
      {"pageup", ImGuiKey_PageUp},
      {"page_up", ImGuiKey_PageUp},
      {"prior", ImGuiKey_PageUp},
      {"pgup", ImGuiKey_PageUp},
      {"pagedown", ImGuiKey_PageDown},
      {"page_down", ImGuiKey_PageDown},
      {"next", ImGuiKey_PageDown},
      {"pgdn", ImGuiKey_PageDown},
      {"f12", kEmergencyStopKey},
  };
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const auto& [known, key] : kNames) {
    if (lower == known) return key;
  }
  return -1;
}

std::vector<ScriptStep> ParseUiScript(const std::string& script, const std::string& source_name) {
  std::vector<ScriptStep> steps;
  std::istringstream lines(script);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a script saved on Windows
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const size_t space = line.find(' ', start);
    const std::string verb =
        line.substr(start, space == std::string::npos ? std::string::npos : space - start);
    std::string argument = space == std::string::npos ? "" : line.substr(space + 1);
    // Trailing blanks are invisible in an editor; a label or a number never ends in one.
    while (!argument.empty() && (argument.back() == ' ' || argument.back() == '\t')) {
      argument.pop_back();
    }
    const std::string where = source_name + ":" + std::to_string(number) + ": ";
    try {
      steps.push_back(ParseStep(verb, argument));
    } catch (const UserError& e) {
      throw UserError(where + e.what());
    }
    steps.back().where = where;
  }
  return steps;
}

}  // namespace recon::ui
