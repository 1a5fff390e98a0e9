#include "devices/uwb/dwm1001_driver.h"

#include <chrono>

#include "engine/core/error.h"

namespace recon::uwb {

namespace {

double SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The bytes that arrived, printable, for an error message.
std::string Shown(const std::string& bytes) {
  std::string out;
  for (char c : bytes.substr(0, 80)) {
    if (c == '\r') {
      out += "\\r";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c >= 32 && c < 127) {
      out += c;
    } else {
      out += '?';
    }
  }
  return out.empty() ? "nothing" : "\"" + out + "\"";
}

}  // namespace

Dwm1001Driver::Dwm1001Driver(std::string port, int answer_timeout_ms)
    : port_(std::move(port)), answer_timeout_ms_(answer_timeout_ms), started_(SteadySeconds()) {
  Start();
}

Dwm1001Driver::~Dwm1001Driver() {
  // Leave the tag as found: stop the stream so the next program meets a quiet shell.
  if (connected()) serial_->Write("lec\r");
}

double Dwm1001Driver::Now() const { return SteadySeconds() - started_; }

void Dwm1001Driver::Start() {
  serial_ = std::make_unique<SerialPort>(port_);
  // The tag boots in binary TLV mode; two carriage returns within a second open the shell. A
  // tag already in the shell (or streaming) answers them with prompts, which the parser skips.
  serial_->Write("\r\r");
  std::string answer;
  const double deadline = SteadySeconds() + answer_timeout_ms_ / 1000.0;
  while (answer.find("dwm>") == std::string::npos && SteadySeconds() < deadline) {
    if (!serial_->Read(answer, 50)) break;
  }
  if (answer.find("dwm>") == std::string::npos) {
    const std::string why = serial_->open() ? "" : " (" + serial_->last_error() + ")";
    serial_.reset();
    throw UserError("no DWM1001 shell answered on " + port_ + " within " +
                    std::to_string(answer_timeout_ms_) + " ms" + why + "; it sent " +
                    Shown(answer) + ". Is it a DWM1001 with the PANS firmware, at 115200 baud?");
  }
  if (!serial_->Write("lec\r"))
    throw UserError("cannot start the stream: " + serial_->last_error());
}

bool Dwm1001Driver::Poll(std::vector<TimedReading>& out, int timeout_ms) {
  if (!connected()) return false;
  std::string bytes;
  const bool alive = serial_->Read(bytes, timeout_ms);
  if (!bytes.empty()) {
    const double now = Now();
    std::vector<UwbReading> readings;
    parser_.Feed(bytes, readings);
    for (UwbReading& r : readings) out.push_back({now, std::move(r)});
  }
  if (!alive) last_error_ = "the DWM1001 on " + serial_->last_error() + " (unplugged?)";
  return alive;
}

void Dwm1001Driver::Reconnect() {
  serial_.reset();
  Start();
  last_error_.clear();
}

}  // namespace recon::uwb
