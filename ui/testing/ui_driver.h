#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/image.h"
#include "engine/core/stepped_clock.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_snapshot.h"
#include "ui/testing/keyboard_person.h"
#include "ui/testing/ui_script.h"
#include "ui/widgets/widget_registry.h"

namespace recon::ui {

/// Plays a script of inputs into a headless studio, as a person at the keyboard and mouse would:
/// click a widget by its label, type, press keys, wait. Each step runs real frames, so clicks go
/// through ImGui's own hit testing. Used by the screenshot tests and by `recon-studio --script`.
class UiDriver {
 public:
  /// `draw` issues the whole window's ImGui calls for one frame (it is called once per frame).
  UiDriver(HeadlessWindow& window, std::function<void()> draw);

  /// Runs one frame with `input`. With a clock (SetClock), the frame then moves the clock on by
  /// kFrameStep once the application has taken in what the frame sent, and waits for it to
  /// catch up.
  void Frame(const FrameInput& input = {});
  void WaitFrames(int frames);
  /// Moves the pointer to the widget labelled `label` and clicks it (hover, press, release).
  /// Throws UserError if no such widget was drawn, naming the labels that were, or if it is
  /// disabled.
  void Click(const std::string& label);
  /// Clicks at (x, y) in the window, whatever lies there (a row's cell away from its label).
  void ClickAt(float x, float y);
  /// Moves the pointer onto the widget labelled `label`, enabled or not, without pressing: what a
  /// person does to read why a control is disabled. UserError if no such widget was drawn.
  void PointAt(const std::string& label);
  /// Presses the left button on the widget labelled `label`, moves the pointer by (dx, dy)
  /// pixels over a few frames and lets go: a drag. UserError as Click.
  void Drag(const std::string& label, float dx, float dy);
  /// Turns the mouse wheel by `notches` (positive: away from the user) over the widget labelled
  /// `label`. UserError as Click.
  void Scroll(const std::string& label, float notches);
  /// Types text into the focused widget.
  void Type(const std::string& text);
  /// Presses and releases a key (an ImGuiKey value).
  void Press(int imgui_key);
  /// Holds a key (an ImGuiKey value) down for `seconds` (of the clock's time), drawing frames
  /// meanwhile,
  /// then releases it: what a teacher does with an arrow key to drive the arm.
  void Hold(int imgui_key, double seconds);
  /// Scrolls the panels holding the widget labelled `label` until all of it is in view, as a
  /// person scrolls to what lies below the fold, and returns where it lies then. UserError when
  /// it was not drawn or scrolling cannot bring it in.
  WidgetPlacement ScrollIntoView(const std::string& label);
  /// Whether a widget labelled `label` was drawn in the last frame.
  bool Drawn(const std::string& label) const;
  RgbImage Screenshot() { return window_.Screenshot(); }

  /// Whether the application has taken in every command the UI sent (e.g. the controller has
  /// handled them and published a snapshot showing it). When set, Click waits for it, so the next
  /// line of a script sees the click's effect.
  void SetSettledCheck(std::function<bool()> settled) { settled_ = std::move(settled); }
  /// Whether the application was asked to close (e.g. Session > Quit): RunScript stops after the
  /// step that asked.
  void SetQuitCheck(std::function<bool()> quit) { quit_ = std::move(quit); }
  /// What `wait-idle` waits for (e.g. "the studio's controller has nothing running").
  void SetIdleCheck(std::function<bool()> idle) { idle_ = std::move(idle); }
  /// Plays the application on `clock`: each frame moves it kFrameStep on, then waits (60 s of
  /// wall time at most) until `caught_up(time)` says the application has run at that time. What
  /// a script does then depends on its frames only, never on how fast the machine is.
  void SetClock(std::shared_ptr<SteppedClock> clock,
                std::function<bool(SteppedClock::time_point)> caught_up);
  /// A frame's studio time on a clock: a 50 Hz display, five frames to a control period.
  static constexpr std::chrono::milliseconds kFrameStep{20};
  /// What the screens show now (the application's latest snapshot), for the scripted person.
  void SetSnapshotSource(std::function<StudioSnapshot()> source) { snapshot_ = std::move(source); }
  /// Gives the keyboard take that has just been started (on the Record screen, Keyboard chosen)
  /// as KeyboardPerson would, one frame of keys at a time, until the take ends. UserError when
  /// no take runs, the person loses track, or it takes longer than `timeout_s`. Returns the
  /// person, to ask how it went. `pace`: the ideal person by default, or a realistic one
  /// (PersonPace::Realistic).
  KeyboardPerson KeyboardTake(double timeout_s, const PersonPace& pace = {});
  /// What PersonTakes cost.
  struct PersonTakesResult {
    int kept = 0, tries = 0, grasp_attempts = 0;
    double kept_seconds = 0, total_seconds = 0;  ///< recorded, from the takes' sample counts
  };
  /// The realistic person (PersonPace::Realistic, seeded by `seed` and the try) records
  /// `demonstrations` takes in which the task is done, from the Record screen (Keyboard chosen):
  /// Start recording, the take, and Discard when it ended undone (or the person lost track), up
  /// to `max_tries` tries per demonstration. UserError when one needs more.
  PersonTakesResult PersonTakes(int demonstrations, uint64_t seed, int max_tries = 8);
  /// Runs frames until the idle check holds; UserError after `timeout_s` seconds.
  void WaitIdle(double timeout_s);
  /// Where `screenshot` writes relative paths (default: the working directory).
  void SetScreenshotDir(const std::string& dir) { screenshot_dir_ = dir; }

  /// Runs a script, one command per line: `click <label>`, `type <text>`, `press <key>`
  /// (enter, tab, escape, backspace, space, up, down, left, right, pageup, pagedown),
  /// `hold <key> <seconds>`, `wait <frames>`, `sleep <seconds>` (frames for that long),
  /// `wait-idle [seconds]`, `keyboard-take [seconds]`, `screenshot <file.png>` (inside the
  /// screenshot folder); `#` starts a comment. The whole script is checked before its first line
  /// runs (ParseUiScript); every error names the script and line.
  void RunScript(const std::string& script, const std::string& source_name = "script");

 private:
  void RunStep(const ScriptStep& step);
  /// Where the widget labelled `label` was drawn; UserError when it was not or is disabled.
  WidgetRect Locate(const std::string& label, bool enabled_only = true);
  void Hover(float x, float y, bool down);
  /// The application's time: the clock's if one is set, the steady clock's otherwise.
  SteppedClock::time_point Now() const;
  /// Waits until the application has taken in every command sent (the settled check).
  void WaitSettled(const std::string& what);
  /// Waits (wall time, 60 s at most) until `done`; UserError "<failure> within 60 s" after.
  static void WaitUntil(const std::function<bool()>& done, const std::string& failure);

  HeadlessWindow& window_;
  std::function<void()> draw_;
  float mouse_x_ = FrameInput::kNoMouse;
  float mouse_y_ = FrameInput::kNoMouse;
  std::function<bool()> idle_;
  std::function<bool()> settled_;
  std::function<bool()> quit_;
  std::function<StudioSnapshot()> snapshot_;
  std::string screenshot_dir_;
  std::shared_ptr<SteppedClock> clock_;
  std::function<bool(SteppedClock::time_point)> caught_up_;
};

}  // namespace recon::ui
