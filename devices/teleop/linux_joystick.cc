#include "devices/teleop/linux_joystick.h"

#include <fcntl.h>
#include <linux/joystick.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"

namespace recon::teleop {

namespace {
constexpr size_t kEventBytes = sizeof(js_event);
static_assert(kEventBytes == 8, "the joystick API's events are 8 bytes");
constexpr size_t kMaxAxes = 64, kMaxButtons = 128;  // more means a corrupt stream
}  // namespace

LinuxJoystick::LinuxJoystick(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    throw UserError("cannot open the gamepad " + path_ + ": " + std::strerror(errno));
  }
  char name[128] = {};
  if (::ioctl(fd_, JSIOCGNAME(sizeof(name) - 1), name) >= 0 && name[0] != '\0') name_ = name;
}

LinuxJoystick::~LinuxJoystick() {
  if (fd_ >= 0) ::close(fd_);
}

void LinuxJoystick::Close(const std::string& why) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  last_error_ = why;
}

bool LinuxJoystick::Poll() {
  if (fd_ < 0) return false;
  unsigned char buffer[64 * kEventBytes];
  for (;;) {
    const ssize_t n = ::read(fd_, buffer, sizeof(buffer));
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return true;
      Close("the gamepad " + path_ + " is gone: " + std::strerror(errno));  // ENODEV: unplugged
      return false;
    }
    if (n == 0) {
      // A device never ends; a FIFO whose writer went away does.
      Close("the gamepad " + path_ + " closed");
      return false;
    }
    pending_.insert(pending_.end(), buffer, buffer + n);
    size_t used = 0;
    for (; used + kEventBytes <= pending_.size(); used += kEventBytes) Apply(&pending_[used]);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(used));
  }
}

void LinuxJoystick::Apply(const unsigned char* bytes) {
  js_event event;
  std::memcpy(&event, bytes, kEventBytes);
  ++events_;
  state_.time_ms = event.time;
  // JS_EVENT_INIT marks the device's initial state, sent on open: the same as a change.
  const unsigned type = event.type & ~JS_EVENT_INIT;
  if (type == JS_EVENT_AXIS && event.number < kMaxAxes) {
    if (state_.axes.size() <= event.number) state_.axes.resize(event.number + 1, 0.0f);
    state_.axes[event.number] = std::clamp(event.value / 32767.0f, -1.0f, 1.0f);
  } else if (type == JS_EVENT_BUTTON && event.number < kMaxButtons) {
    if (state_.buttons.size() <= event.number) state_.buttons.resize(event.number + 1, false);
    state_.buttons[event.number] = event.value != 0;
  }
  // Anything else (an unknown type, an absurd number) is ignored: a gamepad is not worth a crash.
}

std::vector<std::string> LinuxJoystick::Find(const std::string& directory) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("js", 0) == 0 && name.size() > 2 &&
        std::all_of(name.begin() + 2, name.end(), ::isdigit)) {
      found.push_back(entry.path().string());
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace recon::teleop
