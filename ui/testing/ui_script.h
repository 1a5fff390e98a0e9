#pragma once

// The studio's input scripts (`recon-studio --script`, the screenshot tests), parsed in full
// before the first line runs: a typo or an out-of-range number on line 40 is reported before
// lines 1-39 have spent ten minutes training, and nothing a script names can reach outside the
// folder its screenshots go to.

#include <cstdint>
#include <string>
#include <vector>

namespace recon::ui {

struct ScriptStep {
  enum class Verb {
    kClick,
    kType,
    kPress,
    kHold,
    kWait,
    kSleep,
    kWaitIdle,
    kKeyboardTake,
    kPersonTakes,
    kScreenshot
  };
  Verb verb = Verb::kWait;
  /// "file:line: ", the prefix of every error this step raises while it runs.
  std::string where;
  /// click: the widget's label; type: the text; screenshot: the file, relative to the
  /// screenshot folder.
  std::string text;
  int key = -1;        ///< press, hold: an ImGuiKey value
  double seconds = 0;  ///< hold, sleep, wait-idle, keyboard-take
  int frames = 0;      ///< wait; person-takes: the demonstrations to keep
  uint64_t seed = 0;   ///< person-takes: the realistic person's seed
};

/// The longest hold, sleep, wait-idle or keyboard-take a script may ask for, and the most frames a
/// wait may.
inline constexpr double kMaxScriptSeconds = 3600.0;
inline constexpr int kMaxScriptFrames = 100000;

/// Parses every line of `script` (one command per line, `#` starts a comment). UserError
/// "<source_name>:<line>: ..." for an unknown command or key, a number that is not one, out of
/// range or has trailing characters, a missing argument, or a screenshot name that is absolute,
/// climbs out with "..", or does not end in .png.
std::vector<ScriptStep> ParseUiScript(const std::string& script, const std::string& source_name);

/// The io.KeysDown slot a script's key name stands for, or -1: enter, tab, escape, backspace,
/// delete, insert, home, end, space, the arrows (up, down, left, right), pageup, pagedown and f12
/// (the e-stop, kEmergencyStopKey), with the usual synonyms (return, esc, pgup, pgdn,
/// arrowup, ...), in any case.
int ScriptKeyNamed(const std::string& name);

}  // namespace recon::ui
