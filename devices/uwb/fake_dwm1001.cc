#include "devices/uwb/fake_dwm1001.h"

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "devices/uwb/lec_format.h"
#include "devices/uwb/tlv_codec.h"
#include "engine/core/error.h"

namespace recon::uwb {

namespace {

// The firmware drops an incomplete TLV request after a short silence and answers it as a stray
// byte; a lone carriage return waits up to a second for its twin (the shell's "\r\r").
constexpr auto kRequestTimeout = std::chrono::milliseconds(50);
constexpr auto kCarriageReturnTimeout = std::chrono::milliseconds(1000);

}  // namespace

FakeDwm1001::FakeDwm1001(Options options)
    : options_(std::move(options)), period_ms_(options_.period_ms) {
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
    throw UserError(std::string("cannot open a pseudo-terminal: ") + std::strerror(errno));
  }
  const char* name = ::ptsname(master_);
  if (name == nullptr) throw UserError("cannot name the pseudo-terminal");
  port_ = name;
  // Raw on the master's side too, so the bytes go out as the firmware sends them.
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
    } else {
      return;  // nobody reads (EAGAIN): lost, as on a real port whose buffer is full
    }
  }
}

void FakeDwm1001::Handle(char c) {
  if (!in_shell_) {
    HandleTlvByte(c);
    return;
  }
  if (c == '\n') return;
  if (c != '\r') {
    command_ += c;
    return;
  }
  const std::string command = command_;
  command_.clear();
  Send(command + "\r\n");  // the shell echoes
  HandleShellCommand(command);
}

void FakeDwm1001::HandleShellCommand(const std::string& command) {
  if (command == "lec") {
    streaming_ = !streaming_;
  } else if (command == "quit") {
    streaming_ = false;
    in_shell_ = false;
    return;
  } else if (command == "si") {
    char line[256];
    std::snprintf(line, sizeof(line),
                  "[000012.345 INF] sys: fw2 fw_ver=x01030001 cfg_ver=x00010700\r\n"
                  "[000012.345 INF] uwb0: panid=x1234 addr=x%016" PRIX64
                  "\r\n"
                  "[000012.346 INF] mode: tn (act,twr,np,nole)\r\n",
                  options_.node_id);
    Send(line);
  } else if (!command.empty()) {
    Send("unknown command\r\n");
  }
  if (!streaming_) Send("dwm> ");
}

void FakeDwm1001::HandleTlvByte(char c) {
  last_request_byte_ = Clock::now();
  if (request_.empty() && c == '\r') {
    if (pending_cr_) {
      pending_cr_ = false;
      in_shell_ = true;
      Send("\r\nDWM1001 TWR Real Time Location System\r\n\r\ndwm> ");
      return;
    }
    pending_cr_ = true;
    return;
  }
  if (pending_cr_) {
    // The carriage return was the type byte of a request after all.
    pending_cr_ = false;
    request_.push_back('\r');
  }
  request_.push_back(c);
  if (request_.size() >= 2 &&
      request_.size() == 2 + static_cast<size_t>(static_cast<uint8_t>(request_[1]))) {
    AnswerTlv();
    request_.clear();
  }
}

void FakeDwm1001::ExpireTlvRequest() {
  if (in_shell_ || (request_.empty() && !pending_cr_)) return;
  const auto silence = Clock::now() - last_request_byte_;
  if (silence < (pending_cr_ ? kCarriageReturnTimeout : kRequestTimeout)) return;
  request_.clear();
  pending_cr_ = false;
  ++tlv_requests_;
  Send(EncodeStatus(tlv::kUnknownTlv));
}

void FakeDwm1001::AnswerTlv() {
  ++tlv_requests_;
  const auto type = static_cast<uint8_t>(request_[0]);
  const size_t length = request_.size() - 2;
  const auto* value = reinterpret_cast<const unsigned char*>(request_.data() + 2);
  std::string answer;
  try {
    if (type == tlv::kPosGet && length == 0) {
      answer = EncodeStatus(tlv::kOk) + EncodePosition(current_);
    } else if (type == tlv::kLocGet && length == 0) {
      answer =
          EncodeStatus(tlv::kOk) + EncodePosition(current_) + EncodeAnchorList(current_.anchors);
    } else if (type == tlv::kNodeIdGet && length == 0) {
      answer = EncodeStatus(tlv::kOk) + EncodeNodeId(options_.node_id);
    } else if (type == tlv::kUpdRateSet && length == 4) {
      const int active = value[0] | value[1] << 8;
      if (active >= 1 && active <= 600) {
        period_ms_ = active * 100;
        answer = EncodeStatus(tlv::kOk);
      } else {
        answer = EncodeStatus(tlv::kInvalidParameter);
      }
    } else {
      answer = EncodeStatus(tlv::kUnknownTlv);
    }
  } catch (const std::invalid_argument&) {
    answer = EncodeStatus(tlv::kInternal);  // a reading the firmware could not have produced
  }
  Send(answer);
}

void FakeDwm1001::Update() {
  if (options_.next_reading) current_ = options_.next_reading();
  if (!streaming_) return;
  std::string update;
  if (options_.next_update) {
    update = options_.next_update();
  } else if (options_.next_reading) {
    try {
      update = FormatLecLine(current_);
    } catch (const std::invalid_argument&) {
      update.clear();  // the firmware would have printed nothing usable
    }
  }
  if (!update.empty()) Send(update);
  ++updates_sent_;
}

void FakeDwm1001::Run() {
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
    ExpireTlvRequest();
    if (Clock::now() >= next) {
      next += std::chrono::milliseconds(period_ms_.load());
      Update();
    }
  }
}

}  // namespace recon::uwb
