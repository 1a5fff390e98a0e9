#include "devices/robot/urscript_command.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/core/error.h"

namespace recon::robot {

namespace {

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.12g", value);
  return text;
}

void RequirePositiveAcceleration(double a, const char* what) {
  if (!std::isfinite(a) || a <= 0) {
    throw UserError(std::string("refusing to send ") + what + " with acceleration " + Number(a) +
                    " rad/s^2 (must be a positive number)");
  }
}

/// A cursor over one script line; each Take* skips spaces first and fails for good on a mismatch.
class Cursor {
 public:
  explicit Cursor(const std::string& text) : text_(text) {}
  bool ok() const { return ok_; }
  bool Take(char c) {
    SkipSpaces();
    if (ok_ && at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    ok_ = false;
    return false;
  }
  bool Peek(char c) {
    SkipSpaces();
    return at_ < text_.size() && text_[at_] == c;
  }
  bool TakeWord(const std::string& word) {
    SkipSpaces();
    if (ok_ && text_.compare(at_, word.size(), word) == 0) {
      at_ += word.size();
      return true;
    }
    ok_ = false;
    return false;
  }
  double TakeNumber() {
    SkipSpaces();
    if (!ok_ || at_ >= text_.size()) return Fail();
    // strtod also takes "nan", "inf" and hex; URScript numbers are plain decimals.
    const char first = text_[at_];
    if (!(std::isdigit(static_cast<unsigned char>(first)) || first == '-' || first == '+' ||
          first == '.')) {
      return Fail();
    }
    const char* begin = text_.c_str() + at_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v)) return Fail();
    for (const char* p = begin; p < end; ++p) {
      if (*p == 'x' || *p == 'X' || *p == 'n' || *p == 'N' || *p == 'i' || *p == 'I') {
        return Fail();
      }
    }
    at_ += static_cast<size_t>(end - begin);
    return v;
  }
  bool AtEnd() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    return ok_ && at_ == text_.size();
  }

 private:
  void SkipSpaces() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t')) ++at_;
  }
  double Fail() {
    ok_ = false;
    return 0;
  }
  const std::string& text_;
  size_t at_ = 0;
  bool ok_ = true;
};

}  // namespace

std::string FormatSpeedJ(const std::array<double, 6>& velocity_rad_s, double acceleration_rad_s2,
                         double time_s) {
  for (size_t i = 0; i < 6; ++i) {
    if (!std::isfinite(velocity_rad_s[i])) {
      throw UserError("refusing to send speedj with a non-finite velocity for joint " +
                      std::to_string(i + 1) + " (" + Number(velocity_rad_s[i]) + ")");
    }
  }
  RequirePositiveAcceleration(acceleration_rad_s2, "speedj");
  if (!std::isfinite(time_s) || time_s < 0) {
    throw UserError("refusing to send speedj with t = " + Number(time_s) + " s");
  }
  std::string line = "speedj([";
  for (size_t i = 0; i < 6; ++i) {
    if (i > 0) line += ',';
    line += Number(velocity_rad_s[i]);
  }
  return line + "]," + Number(acceleration_rad_s2) + "," + Number(time_s) + ")\n";
}

std::string FormatStopJ(double acceleration_rad_s2) {
  RequirePositiveAcceleration(acceleration_rad_s2, "stopj");
  return "stopj(" + Number(acceleration_rad_s2) + ")\n";
}

std::string FormatSetToolDigitalOut(int output, bool value) {
  if (output < 0 || output > 1) {
    throw UserError("a UR tool has digital outputs 0 and 1, not " + std::to_string(output));
  }
  return "set_tool_digital_out(" + std::to_string(output) + "," + (value ? "True" : "False") +
         ")\n";
}

std::optional<UrScriptCommand> ParseUrScriptLine(const std::string& line) {
  Cursor c(line);
  UrScriptCommand command;
  if (c.TakeWord("speedj")) {
    command.kind = UrScriptCommand::Kind::kSpeedJ;
    c.Take('(');
    c.Take('[');
    for (size_t i = 0; i < 6; ++i) {
      if (i > 0) c.Take(',');
      command.velocity_rad_s[i] = c.TakeNumber();
    }
    c.Take(']');
    c.Take(',');
    command.acceleration_rad_s2 = c.TakeNumber();
    if (c.Peek(',')) {
      c.Take(',');
      command.time_s = c.TakeNumber();
    }
    c.Take(')');
    if (!c.AtEnd() || command.acceleration_rad_s2 <= 0 || command.time_s < 0) return std::nullopt;
    return command;
  }
  Cursor s(line);
  if (s.TakeWord("stopj")) {
    command.kind = UrScriptCommand::Kind::kStopJ;
    s.Take('(');
    command.acceleration_rad_s2 = s.TakeNumber();
    s.Take(')');
    if (!s.AtEnd() || command.acceleration_rad_s2 <= 0) return std::nullopt;
    return command;
  }
  Cursor t(line);
  if (t.TakeWord("set_tool_digital_out")) {
    command.kind = UrScriptCommand::Kind::kSetToolDigitalOut;
    t.Take('(');
    const double output = t.TakeNumber();
    t.Take(',');
    if (t.Peek('T')) {
      command.tool_value = t.TakeWord("True");
    } else {
      t.TakeWord("False");
      command.tool_value = false;
    }
    t.Take(')');
    if (!t.AtEnd() || (output != 0 && output != 1)) return std::nullopt;
    command.tool_output = static_cast<int>(output);
    return command;
  }
  return std::nullopt;
}

}  // namespace recon::robot
