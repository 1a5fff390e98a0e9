#include "devices/uwb/fake_dwm1001.h"

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "engine/core/error.h"

namespace recon::uwb {

FakeDwm1001::FakeDwm1001(Options options) : options_(std::move(options)) {
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
    throw UserError(std::string("cannot open a pseudo-terminal: ") + std::strerror(errno));
  }
  const char* name = ::ptsname(master_);
  if (name == nullptr) throw UserError("cannot name the pseudo-terminal");
  port_ = name;
  // Raw on the master's side too, so the lines go out as the firmware prints them.
  termios tty{};
  if (::tcgetattr(master_, &tty) == 0) {
    ::cfmakeraw(&tty);
    ::tcsetattr(master_, TCSANOW, &tty);
  }
  ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
  thread_ = std::thread([this] { Run(); });
}

FakeDwm1001::~FakeDwm1001() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  Unplug();
}

void FakeDwm1001::Unplug() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (master_ >= 0) ::close(master_);
  master_ = -1;
  streaming_ = false;
}

void FakeDwm1001::Send(const std::string& bytes) {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t done = 0;
  while (master_ >= 0 && done < bytes.size()) {
    const ssize_t n = ::write(master_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
    } else if (n < 0 && errno == EAGAIN) {
      return;  // nobody reads: the line is lost, as on a real port whose buffer is full
    } else {
      return;
    }
  }
}

void FakeDwm1001::Handle(char c) {
  if (!in_shell_) {
    // Binary TLV mode: two carriage returns within a second open the shell.
    carriage_returns_ = c == '\r' ? carriage_returns_ + 1 : 0;
    if (carriage_returns_ >= 2) {
      in_shell_ = true;
      carriage_returns_ = 0;
      Send("\r\nDWM1001 TWR Real Time Location System\r\n\r\ndwm> ");
    }
    return;
  }
  if (c != '\r' && c != '\n') {
    command_ += c;
    return;
  }
  if (c == '\n') return;
  const std::string command = command_;
  command_.clear();
  Send(command + "\r\n");  // the shell echoes
  if (command == "lec") {
    streaming_ = !streaming_;
  } else if (command == "quit") {
    streaming_ = false;
    in_shell_ = false;
    return;
  } else if (!command.empty()) {
    Send("unknown command\r\n");
  }
  if (!streaming_) Send("dwm> ");
}

void FakeDwm1001::Run() {
  using Clock = std::chrono::steady_clock;
  auto next = Clock::now();
  while (!stop_) {
    int fd;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      fd = master_;
    }
    if (fd < 0) return;
    const int wait_ms = static_cast<int>(std::max<int64_t>(
        0, std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count()));
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, std::min(wait_ms, 20)) > 0) {
      if (p.revents & POLLIN) {
        char buffer[256];
        const ssize_t n = ::read(fd, buffer, sizeof(buffer));
        for (ssize_t i = 0; i < n; ++i) Handle(buffer[i]);
      } else if (p.revents & POLLHUP) {
        // No one has the port open (yet, or any more): a master polls as hung up meanwhile.
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    }
    if (Clock::now() >= next) {
      next += std::chrono::milliseconds(options_.period_ms);
      if (streaming_ && options_.next_update) {
        const std::string update = options_.next_update();
        if (!update.empty()) Send(update);
        ++updates_sent_;
      }
    }
  }
}

}  // namespace recon::uwb
