#include "ui/testing/ui_driver.h"

#include <imgui.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <thread>

#include "engine/core/error.h"
#include "engine/report/image_png.h"
#include "ui/widgets/widget_registry.h"

namespace recon::ui {

namespace {

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "(none)" : out;
}

int KeyNamed(const std::string& name) {
  if (name == "enter") return ImGuiKey_Enter;
  if (name == "tab") return ImGuiKey_Tab;
  if (name == "escape") return ImGuiKey_Escape;
  if (name == "backspace") return ImGuiKey_Backspace;
  if (name == "space") return ImGuiKey_Space;
  if (name == "up") return ImGuiKey_UpArrow;
  if (name == "down") return ImGuiKey_DownArrow;
  if (name == "left") return ImGuiKey_LeftArrow;
  if (name == "right") return ImGuiKey_RightArrow;
  if (name == "pageup") return ImGuiKey_PageUp;
  if (name == "pagedown") return ImGuiKey_PageDown;
  return -1;
}

}  // namespace

UiDriver::UiDriver(HeadlessWindow& window, std::function<void()> draw)
    : window_(window), draw_(std::move(draw)) {}

void UiDriver::Frame(const FrameInput& input) {
  window_.Frame(input, [&] {
    WidgetRegistry::ForThisThread().BeginFrame();
    draw_();
  });
}

void UiDriver::WaitFrames(int frames) {
  FrameInput idle;
  idle.mouse_x = mouse_x_;
  idle.mouse_y = mouse_y_;
  for (int i = 0; i < frames; ++i) Frame(idle);
}

void UiDriver::Hover(float x, float y, bool down) {
  mouse_x_ = x;
  mouse_y_ = y;
  FrameInput input;
  input.mouse_x = x;
  input.mouse_y = y;
  input.mouse_down[0] = down;
  Frame(input);
}

void UiDriver::Click(const std::string& label) {
  if (!Drawn(label)) Frame();  // the widget may appear only once the frame has been drawn
  const std::optional<WidgetRect> rect = WidgetRegistry::ForThisThread().Find(label);
  if (!rect) {
    throw UserError("no widget labelled '" + label +
                    "' on screen; drawn: " + Join(WidgetRegistry::ForThisThread().Labels()));
  }
  if (!rect->enabled) throw UserError("the widget '" + label + "' is disabled");
  Hover(rect->CentreX(), rect->CentreY(), false);
  Hover(rect->CentreX(), rect->CentreY(), true);
  Hover(rect->CentreX(), rect->CentreY(), false);
  if (settled_) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!settled_()) {
      if (std::chrono::steady_clock::now() > deadline) {
        throw UserError("clicking '" + label + "' was not taken in within 60 s");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    WaitFrames(2);  // draw what the application now shows
  }
}

void UiDriver::Type(const std::string& text) {
  FrameInput input;
  input.mouse_x = mouse_x_;
  input.mouse_y = mouse_y_;
  for (unsigned char c : text) input.characters.push_back(c);
  Frame(input);
}

void UiDriver::Press(int imgui_key) {
  FrameInput input;
  input.mouse_x = mouse_x_;
  input.mouse_y = mouse_y_;
  input.keys_pressed.push_back(imgui_key);
  Frame(input);
  WaitFrames(1);  // released
}

void UiDriver::Hold(int imgui_key, double seconds) {
  FrameInput input;
  input.mouse_x = mouse_x_;
  input.mouse_y = mouse_y_;
  input.keys_down.push_back(imgui_key);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  do {
    Frame(input);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  } while (std::chrono::steady_clock::now() < until);
  WaitFrames(1);  // released
  if (settled_) {
    // What the key sent must be taken in before the next line acts on its effect.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!settled_() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    WaitFrames(2);
  }
}

void UiDriver::WaitIdle(double timeout_s) {
  if (!idle_) throw UserError("wait-idle needs an idle check (none was set)");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  WaitFrames(2);
  while (!idle_()) {
    if (std::chrono::steady_clock::now() > deadline) {
      throw UserError("still busy after " + std::to_string(static_cast<int>(timeout_s)) + " s");
    }
    WaitFrames(1);
    // About 30 frames a second while waiting: a software-rendered 1280 x 800 frame costs the
    // same CPU the job being waited for needs (llvmpipe's threads are shared).
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  WaitFrames(3);  // let the screens show the finished state
}

bool UiDriver::Drawn(const std::string& label) const {
  return WidgetRegistry::ForThisThread().Find(label).has_value();
}

void UiDriver::RunScript(const std::string& script, const std::string& source_name) {
  std::istringstream lines(script);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const size_t space = line.find(' ', start);
    const std::string verb =
        line.substr(start, space == std::string::npos ? std::string::npos : space - start);
    const std::string argument = space == std::string::npos ? "" : line.substr(space + 1);
    const std::string where = source_name + ":" + std::to_string(number) + ": ";
    try {
      if (verb == "click") {
        Click(argument);
      } else if (verb == "type") {
        Type(argument);
      } else if (verb == "press") {
        const int key = KeyNamed(argument);
        if (key < 0) throw UserError("unknown key '" + argument + "'");
        Press(key);
      } else if (verb == "hold") {
        // hold <key> <seconds>: a key held down, e.g. an arrow driving the arm.
        const size_t gap = argument.find(' ');
        const std::string name = argument.substr(0, gap);
        const int key = KeyNamed(name);
        if (key < 0) throw UserError("unknown key '" + name + "'");
        if (gap == std::string::npos) throw UserError("hold needs seconds: hold <key> <seconds>");
        const double seconds = std::stod(argument.substr(gap + 1));
        if (!(seconds > 0 && seconds <= 600)) {
          throw UserError("hold lasts 0-600 seconds, not " + argument.substr(gap + 1));
        }
        Hold(key, seconds);
      } else if (verb == "sleep") {
        // sleep <seconds>: frames at about 30 a second for that much wall time, e.g. to let a
        // playback or a teleop run as long as a person would watch it.
        const double seconds = std::stod(argument);
        if (!(seconds > 0 && seconds <= 600)) {
          throw UserError("sleep lasts 0-600 seconds, not " + argument);
        }
        const auto until =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < until) {
          WaitFrames(1);
          std::this_thread::sleep_for(std::chrono::milliseconds(30));
        }
      } else if (verb == "wait") {
        WaitFrames(std::stoi(argument));
      } else if (verb == "wait-idle") {
        WaitIdle(argument.empty() ? 600.0 : std::stod(argument));
      } else if (verb == "screenshot") {
        const std::filesystem::path path(argument);
        report::WritePng(Screenshot(),
                         path.is_absolute() || screenshot_dir_.empty()
                             ? argument
                             : (std::filesystem::path(screenshot_dir_) / path).string());
      } else {
        throw UserError("unknown command '" + verb +
                        "' (click, type, press, hold, wait, sleep, wait-idle, screenshot)");
      }
    } catch (const UserError& e) {
      throw UserError(where + e.what());
    } catch (const std::invalid_argument&) {
      throw UserError(where + "'" + argument + "' is not a number of frames");
    }
  }
}

}  // namespace recon::ui
