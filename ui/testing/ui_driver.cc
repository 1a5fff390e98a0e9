#include "ui/testing/ui_driver.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "engine/core/error.h"
#include "engine/report/image_png.h"
#include "ui/testing/ui_script.h"
#include "ui/widgets/widget_registry.h"

namespace recon::ui {

namespace {

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "(none)" : out;
}

}  // namespace

UiDriver::UiDriver(HeadlessWindow& window, std::function<void()> draw)
    : window_(window), draw_(std::move(draw)) {}

void UiDriver::Frame(const FrameInput& input) {
  window_.Frame(input, [&] {
    WidgetRegistry::ForThisThread().BeginFrame();
    draw_();
  });
  if (!clock_) return;
  // What this frame sent is taken in at the time it showed; only then does time move on, and
  // the next frame shows the application as it is at the new time.
  WaitSettled("a frame");
  clock_->Advance(kFrameStep);
  const SteppedClock::time_point now = clock_->Now();
  WaitUntil([&] { return caught_up_(now); }, "the studio did not catch up with its clock");
}

void UiDriver::WaitUntil(const std::function<bool()>& done, const std::string& failure) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) throw UserError(failure + " within 60 s");
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

void UiDriver::SetClock(std::shared_ptr<SteppedClock> clock,
                        std::function<bool(SteppedClock::time_point)> caught_up) {
  clock_ = std::move(clock);
  caught_up_ = std::move(caught_up);
}

SteppedClock::time_point UiDriver::Now() const {
  return clock_ ? clock_->Now() : std::chrono::steady_clock::now();
}

void UiDriver::WaitSettled(const std::string& what) {
  if (settled_) WaitUntil(settled_, what + " was not taken in");
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

namespace {

/// All of it in view, or, for one larger than the view (a wide table's row), its middle.
bool InView(const WidgetPlacement& p) {
  constexpr float kEdgeSlack_px = 1.0f;
  const auto fits = [&](float min, float max, float view_min, float view_max) {
    if (max - min > view_max - view_min) {
      return (min + max) / 2 >= view_min && (min + max) / 2 <= view_max;
    }
    return min >= view_min - kEdgeSlack_px && max <= view_max + kEdgeSlack_px;
  };
  return fits(p.rect.min_x, p.rect.max_x, p.panel_view.min_x, p.panel_view.max_x) &&
         fits(p.rect.min_y, p.rect.max_y, p.panel_view.min_y, p.panel_view.max_y);
}

/// Moves the scroll of the innermost panel around `p` that scrolls that way by what `p` lies
/// beyond its view (taking effect next frame). False when none can.
bool ScrollTowards(const WidgetPlacement& p) {
  ImGuiWindow* window = ImGui::FindWindowByName(p.panel.c_str());
  const float down = p.rect.max_y - p.panel_view.max_y, up = p.panel_view.min_y - p.rect.min_y;
  float right = p.rect.max_x - p.panel_view.max_x, left = p.panel_view.min_x - p.rect.min_x;
  if (p.rect.max_x - p.rect.min_x > p.panel_view.max_x - p.panel_view.min_x) {
    // Wider than the view: its middle to the view's middle.
    right = (p.rect.min_x + p.rect.max_x - p.panel_view.min_x - p.panel_view.max_x) / 2;
    left = -right;
  }
  bool moved = false;
  // A panel already scrolled as far as it goes hands over to the one holding it (a table's
  // last row below the fold: the table is at its end, the screen is not).
  for (ImGuiWindow* w = window; w != nullptr && !moved; w = w->ParentWindow) {
    const bool can_down = w->Scroll.y<w->ScrollMax.y - 0.5f, can_up = w->Scroll.y> 0.5f;
    if (w->ScrollbarY && ((down > 0 && can_down) || (up > 0 && can_up))) {
      ImGui::SetScrollY(w, w->Scroll.y + (up > 0 ? -up : down));
      moved = true;
    }
    const bool can_right = w->Scroll.x<w->ScrollMax.x - 0.5f, can_left = w->Scroll.x> 0.5f;
    if (w->ScrollbarX && ((right > 0 && can_right) || (left > 0 && can_left))) {
      ImGui::SetScrollX(w, w->Scroll.x + (left > 0 ? -left : right));
      moved = true;
    }
    if ((w->Flags & ImGuiWindowFlags_ChildWindow) == 0) break;
  }
  return moved;
}

}  // namespace

WidgetPlacement UiDriver::ScrollIntoView(const std::string& label) {
  if (!Drawn(label)) Frame();
  for (int attempt = 0; attempt < 6; ++attempt) {
    const std::optional<WidgetPlacement> p = WidgetRegistry::ForThisThread().FindPlacement(label);
    if (!p) {
      throw UserError("no widget labelled '" + label +
                      "' on screen; drawn: " + Join(WidgetRegistry::ForThisThread().Labels()));
    }
    if (InView(*p)) return *p;
    if (!ScrollTowards(*p)) break;
    Frame(FrameInput{});
    WaitFrames(1);
  }
  throw UserError("the widget '" + label + "' lies out of view and scrolling does not bring it in");
}

WidgetRect UiDriver::Locate(const std::string& label, bool enabled_only) {
  if (!Drawn(label)) Frame();  // the widget may appear only once the frame has been drawn
  std::optional<WidgetPlacement> p = WidgetRegistry::ForThisThread().FindPlacement(label);
  if (!p) {
    throw UserError("no widget labelled '" + label +
                    "' on screen; drawn: " + Join(WidgetRegistry::ForThisThread().Labels()));
  }
  // Below the fold: scrolled to first, as a person would.
  if (!InView(*p)) p = ScrollIntoView(label);
  if (enabled_only && !p->rect.enabled) throw UserError("the widget '" + label + "' is disabled");
  return p->rect;
}

void UiDriver::PointAt(const std::string& label) {
  const WidgetRect rect = Locate(label, false);
  Hover(rect.CentreX(), rect.CentreY(), false);
}

void UiDriver::Drag(const std::string& label, float dx, float dy) {
  const WidgetRect rect = Locate(label);
  const float x = rect.CentreX(), y = rect.CentreY();
  Hover(x, y, false);
  Hover(x, y, true);
  constexpr int kSteps = 5;
  for (int i = 1; i <= kSteps; ++i) Hover(x + dx * i / kSteps, y + dy * i / kSteps, true);
  Hover(x + dx, y + dy, false);
}

void UiDriver::Scroll(const std::string& label, float notches) {
  const WidgetRect rect = Locate(label);
  Hover(rect.CentreX(), rect.CentreY(), false);
  FrameInput input;
  input.mouse_x = mouse_x_;
  input.mouse_y = mouse_y_;
  input.wheel = notches;
  Frame(input);
  WaitFrames(1);
}

void UiDriver::ClickAt(float x, float y) {
  Hover(x, y, false);
  Hover(x, y, true);
  Hover(x, y, false);
}

void UiDriver::Click(const std::string& label) {
  const WidgetRect rect = Locate(label);
  ClickAt(rect.CentreX(), rect.CentreY());
  if (settled_) {
    WaitSettled("clicking '" + label + "'");
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
  const auto until = Now() + std::chrono::duration_cast<SteppedClock::duration>(
                                 std::chrono::duration<double>(seconds));
  do {
    Frame(input);
    if (!clock_) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  } while (Now() < until);
  WaitFrames(1);  // released
  if (settled_) {
    // What the key sent must be taken in before the next line acts on its effect.
    WaitSettled("holding a key");
    WaitFrames(2);
  }
}

KeyboardPerson UiDriver::KeyboardTake(double timeout_s, const PersonPace& pace) {
  if (!snapshot_) throw UserError("keyboard-take needs the screen's snapshot (none was set)");
  WaitFrames(2);
  const StudioSnapshot first = snapshot_();
  if (!first.recording || first.teleop != TeleopMode::kKeyboard) {
    throw UserError(
        "keyboard-take: no keyboard take is running (choose Keyboard and click Start "
        "recording first)");
  }
  KeyboardPerson person(pace);
  const auto deadline = Now() + std::chrono::duration_cast<SteppedClock::duration>(
                                    std::chrono::duration<double>(timeout_s));
  while (person.phase() != KeyboardPerson::Phase::kFinished) {
    if (person.phase() == KeyboardPerson::Phase::kLost) {
      throw UserError("keyboard-take: the scripted person gave up: " + person.Describe());
    }
    if (Now() > deadline) {
      throw UserError("keyboard-take: the take still runs after " +
                      std::to_string(static_cast<int>(timeout_s)) + " s; " + person.Describe());
    }
    FrameInput keys = person.Next(snapshot_(), Now());
    keys.mouse_x = mouse_x_;
    keys.mouse_y = mouse_y_;
    Frame(keys);
    // A person looks about 50 times a second at most; the arm moves 10 times a second. (On a
    // clock, each frame is a 50th of a second of the studio's time.)
    if (!clock_) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  WaitFrames(3);  // release the keys and show what became of the take
  return person;
}

UiDriver::PersonTakesResult UiDriver::PersonTakes(int demonstrations, uint64_t seed,
                                                  int max_tries) {
  if (!snapshot_) throw UserError("person-takes needs the screen's snapshot (none was set)");
  PersonTakesResult result;
  for (int demo = 0; demo < demonstrations; ++demo) {
    bool done = false;
    for (int attempt = 0; attempt < max_tries && !done; ++attempt) {
      const size_t before = snapshot_().episodes.size();
      Click("Start recording");
      const uint64_t person_seed = seed * 1000003ULL + static_cast<uint64_t>(result.tries);
      ++result.tries;
      int samples = 0;
      std::string how;
      try {
        const KeyboardPerson person = KeyboardTake(120, PersonPace::Realistic(person_seed));
        result.grasp_attempts += person.grasp_attempts();
        how = person.Describe();
      } catch (const UserError& e) {
        // The person lost track or ran out of patience: the take is given up below.
        how = e.what();
      }
      WaitFrames(3);
      StudioSnapshot s = snapshot_();
      samples = s.recording ? s.recording_samples : 0;
      if (s.episodes.size() > before && s.episodes.back().succeeded) {
        done = true;
        samples = s.episodes.back().samples;
        result.kept_seconds += s.episodes.back().seconds;
      } else {
        if (!s.pending_take.empty()) samples = s.recording_samples;
        if (s.episodes.size() > before) {
          throw UserError("person-takes: a take that was not done was kept");
        }
        Click("Discard");
        WaitFrames(3);
      }
      // Every take counts, kept or not: what the teacher's time is made of.
      result.total_seconds += samples * 0.1;
      std::printf("person-takes: demonstration %d, try %d: %d samples, %s; %s\n", demo + 1,
                  attempt + 1, samples, done ? "done" : "discarded", how.c_str());
    }
    if (!done) {
      throw UserError("person-takes: demonstration " + std::to_string(demo + 1) + " of " +
                      std::to_string(demonstrations) + " was not done in " +
                      std::to_string(max_tries) + " tries");
    }
    ++result.kept;
  }
  return result;
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
  for (const ScriptStep& step : ParseUiScript(script, source_name)) {
    try {
      RunStep(step);
    } catch (const UserError& e) {
      throw UserError(step.where + e.what());
    }
    if (quit_ && quit_()) return;  // the rest of the script would run in a closed window
  }
}

void UiDriver::RunStep(const ScriptStep& step) {
  switch (step.verb) {
    case ScriptStep::Verb::kClick:
      Click(step.text);
      break;
    case ScriptStep::Verb::kType:
      Type(step.text);
      break;
    case ScriptStep::Verb::kPress:
      Press(step.key);
      break;
    case ScriptStep::Verb::kHold:
      Hold(step.key, step.seconds);
      break;
    case ScriptStep::Verb::kWait:
      WaitFrames(step.frames);
      break;
    case ScriptStep::Verb::kSleep: {
      const auto until = Now() + std::chrono::duration_cast<SteppedClock::duration>(
                                     std::chrono::duration<double>(step.seconds));
      while (Now() < until) {
        WaitFrames(1);
        if (!clock_) std::this_thread::sleep_for(std::chrono::milliseconds(30));
      }
      break;
    }
    case ScriptStep::Verb::kWaitIdle:
      WaitIdle(step.seconds);
      break;
    case ScriptStep::Verb::kKeyboardTake:
      KeyboardTake(step.seconds);
      break;
    case ScriptStep::Verb::kPersonTakes: {
      const PersonTakesResult r = PersonTakes(step.frames, step.seed);
      std::printf(
          "person-takes: %d demonstrations kept in %d tries (%d grasp attempts); "
          "%.1f s recorded in kept takes, %.1f s in all (seed %llu)\n",
          r.kept, r.tries, r.grasp_attempts, r.kept_seconds, r.total_seconds,
          static_cast<unsigned long long>(step.seed));
      std::fflush(stdout);
      break;
    }
    case ScriptStep::Verb::kScreenshot:
      // ParseUiScript keeps the name relative and inside the folder.
      report::WritePng(Screenshot(),
                       screenshot_dir_.empty()
                           ? step.text
                           : (std::filesystem::path(screenshot_dir_) / step.text).string());
      break;
  }
}

}  // namespace recon::ui
