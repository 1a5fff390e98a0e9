#include "devices/uwb/dwm1001_driver.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::uwb {

namespace {

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

/// The node id in `si` output ("... addr=xDECA0000000012AB ..."), once its line is complete.
std::optional<uint64_t> FindSiAddress(const std::string& answer) {
  const size_t at = answer.find("addr=x");
  if (at == std::string::npos) return std::nullopt;
  const size_t digits = at + 6;
  if (answer.find('\n', digits) == std::string::npos || answer.size() < digits + 16) {
    return std::nullopt;
  }
  uint64_t id = 0;
  const char* end = answer.data() + digits + 16;
  const auto [ptr, ec] = std::from_chars(answer.data() + digits, end, id, 16);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return id;
}

}  // namespace

Dwm1001Mode ParseDwm1001Mode(const std::string& text) {
  if (text == "lec") return Dwm1001Mode::kLecShell;
  if (text == "tlv") return Dwm1001Mode::kTlvPolling;
  throw UserError("unknown DWM1001 mode \"" + text + "\" (lec or tlv)");
}

const char* Dwm1001ModeName(Dwm1001Mode mode) {
  return mode == Dwm1001Mode::kLecShell ? "lec" : "tlv";
}

std::string NodeIdHex(uint64_t node_id) {
  char text[20];
  std::snprintf(text, sizeof(text), "%016" PRIX64, node_id);
  return text;
}

Dwm1001Driver::Dwm1001Driver(std::string port, int answer_timeout_ms)
    : Dwm1001Driver(std::move(port), Dwm1001Options{.answer_timeout_ms = answer_timeout_ms}) {}

Dwm1001Driver::Dwm1001Driver(std::string port, Dwm1001Options options)
    : port_(std::move(port)), options_(options), started_(SteadySeconds()) {
  Start();
}

Dwm1001Driver::~Dwm1001Driver() {
  // Leave the tag as found: stop the stream so the next program meets a quiet shell.
  if (connected() && options_.mode == Dwm1001Mode::kLecShell) serial_->Write("lec\r");
}

double Dwm1001Driver::Now() const { return SteadySeconds() - started_; }

Dwm1001Counts Dwm1001Driver::counts() const {
  Dwm1001Counts c;
  if (options_.mode == Dwm1001Mode::kLecShell) {
    c.updates = parser_.stats().lines;
    c.readings = parser_.stats().readings;
    c.malformed = parser_.stats().malformed;
  } else {
    const TlvParseStats& s = tlv_parser_.stats();
    for (size_t code = 0; code < s.status_by_code.size(); ++code) {
      c.updates += s.status_by_code[code];
      if (code != 0) c.malformed += s.status_by_code[code];
    }
    c.malformed += s.garbage_runs;
    c.readings = tlv_readings_;
  }
  return c;
}

void Dwm1001Driver::Start() {
  serial_ = std::make_unique<SerialPort>(port_);
  pending_.reset();
  if (options_.mode == Dwm1001Mode::kLecShell) {
    StartShell();
  } else {
    StartTlv();
  }
}

void Dwm1001Driver::StartShell() {
  // The tag boots in binary TLV mode; two carriage returns within a second open the shell. A
  // tag already in the shell (or streaming) answers them with prompts, which the parser skips.
  serial_->Write("\r\r");
  std::string answer;
  const double deadline = SteadySeconds() + options_.answer_timeout_ms / 1000.0;
  while (answer.find("dwm>") == std::string::npos && SteadySeconds() < deadline) {
    if (!serial_->Read(answer, 50)) break;
  }
  const std::string timeout = std::to_string(options_.answer_timeout_ms) + " ms";
  if (answer.find("dwm>") == std::string::npos) {
    const std::string why = serial_->open() ? "" : " (" + serial_->last_error() + ")";
    serial_.reset();
    throw UserError("no DWM1001 shell answered on " + port_ + " within " + timeout + why +
                    "; it sent " + Shown(answer) +
                    ". Is it a DWM1001 with the PANS firmware, at 115200 baud?");
  }
  // `si` names the node; wait for its prompt too, so its lines never reach the lec parser.
  answer.clear();
  serial_->Write("si\r");
  std::optional<uint64_t> id;
  while (SteadySeconds() < deadline) {
    id = FindSiAddress(answer);
    if (id && answer.find("dwm>", answer.find("addr=x")) != std::string::npos) break;
    if (!serial_->Read(answer, 50)) break;
  }
  if (!id) {
    serial_.reset();
    throw UserError("the DWM1001 on " + port_ + " did not report its node id (`si`) within " +
                    timeout + "; it sent " + Shown(answer));
  }
  node_id_ = *id;
  // The prompt is where the echo of "lec" will land: the parser must see it to know the echo
  // as shell traffic rather than a malformed line.
  std::vector<UwbReading> none;
  parser_.Feed(std::string_view(answer).substr(answer.rfind("dwm>")), none);
  if (!serial_->Write("lec\r"))
    throw UserError("cannot start the stream on " + port_ + ": " + serial_->last_error());
}

std::optional<TlvFrame> Dwm1001Driver::TlvExchange(const std::string& request, TlvFrame::Kind kind,
                                                   int timeout_ms, std::string& received) {
  // A private parser: start-up chatter (a shell's echo) must not count against the stream.
  TlvResponseParser parser;
  std::vector<TlvFrame> frames;
  if (!serial_->Write(request)) return std::nullopt;
  const double deadline = SteadySeconds() + timeout_ms / 1000.0;
  while (SteadySeconds() < deadline) {
    std::string bytes;
    if (!serial_->Read(bytes, 20)) return std::nullopt;
    received += bytes;
    parser.Feed(bytes, frames);
    for (const TlvFrame& f : frames) {
      // A failed status answers the request too: report it to the caller.
      if (f.kind == kind || (f.kind == TlvFrame::Kind::kStatus && f.error != tlv::kOk)) return f;
    }
    frames.clear();
  }
  return std::nullopt;
}

void Dwm1001Driver::StartTlv() {
  const int timeout_ms = options_.answer_timeout_ms;
  std::string received;
  // A tag someone left in the shell ignores TLV; "quit" brings it back (in TLV mode the same
  // bytes are a broken request, answered with an error and otherwise harmless).
  std::optional<TlvFrame> id =
      TlvExchange(EncodeNodeIdGet(), TlvFrame::Kind::kNodeId, std::min(timeout_ms, 500), received);
  if (!id || id->kind != TlvFrame::Kind::kNodeId) {
    if (serial_->open()) serial_->Write("\rquit\r");
    std::string ignored;
    if (serial_->open()) serial_->Read(ignored, 100);
    id = TlvExchange(EncodeNodeIdGet(), TlvFrame::Kind::kNodeId, timeout_ms, received);
  }
  if (!id || id->kind != TlvFrame::Kind::kNodeId) {
    const std::string why = serial_->open() ? "" : " (" + serial_->last_error() + ")";
    serial_.reset();
    throw UserError("no DWM1001 answered the TLV node_id_get on " + port_ + " within " +
                    std::to_string(timeout_ms) + " ms" + why + "; it sent " + Shown(received) +
                    ". Is it a DWM1001 with the PANS firmware, at 115200 baud?");
  }
  node_id_ = id->node_id;
  const int units = std::clamp((options_.update_period_ms + 50) / 100, 1, 600);
  const std::optional<TlvFrame> status =
      TlvExchange(EncodeUpdRateSet(units, units), TlvFrame::Kind::kStatus, timeout_ms, received);
  if (!status || status->error != tlv::kOk) {
    serial_.reset();
    throw UserError("the DWM1001 on " + port_ + " refused upd_rate_set (" +
                    (status ? "error " + std::to_string(status->error) : "no answer") + ")");
  }
  next_request_s_ = SteadySeconds();
}

void Dwm1001Driver::HandleFrames(std::vector<TlvFrame>& frames, double now,
                                 std::vector<TimedReading>& out) {
  auto flush = [&] {
    if (!pending_) return;
    out.push_back({now, std::move(*pending_)});
    pending_.reset();
    ++tlv_readings_;
  };
  for (TlvFrame& frame : frames) {
    switch (frame.kind) {
      case TlvFrame::Kind::kPosition:
        flush();
        pending_ = std::move(frame.reading);
        // The location engine reports an all-zero position with quality 0 until it has a fix.
        if (pending_->quality == 0 && pending_->x_m == 0 && pending_->y_m == 0 &&
            pending_->z_m == 0) {
          pending_->has_position = false;
        }
        break;
      case TlvFrame::Kind::kAnchorList:
        if (!pending_) pending_ = UwbReading{};
        pending_->anchors = std::move(frame.reading.anchors);
        flush();
        break;
      case TlvFrame::Kind::kNodeId:
        node_id_ = frame.node_id;
        break;
      case TlvFrame::Kind::kStatus:
        flush();  // the previous response has ended
        break;
    }
  }
}

bool Dwm1001Driver::Poll(std::vector<TimedReading>& out, int timeout_ms) {
  if (!connected()) return false;
  int wait_ms = timeout_ms;
  if (options_.mode == Dwm1001Mode::kTlvPolling) {
    const double period_s = options_.update_period_ms / 1000.0;
    const double now = SteadySeconds();
    if (now >= next_request_s_) {
      if (!serial_->Write(EncodeLocGet())) {
        last_error_ = "the DWM1001 on " + serial_->last_error() + " (unplugged?)";
        return false;
      }
      // Keep the cadence, but never send a burst to catch up after a stall.
      next_request_s_ = std::max(next_request_s_ + period_s, now);
    }
    const int until_next_ms =
        static_cast<int>(std::ceil((next_request_s_ - SteadySeconds()) * 1000.0));
    wait_ms = std::clamp(until_next_ms, 0, timeout_ms);
  }
  std::string bytes;
  const bool alive = serial_->Read(bytes, wait_ms);
  if (!bytes.empty()) {
    const double now = Now();
    if (options_.mode == Dwm1001Mode::kLecShell) {
      std::vector<UwbReading> readings;
      parser_.Feed(bytes, readings);
      for (UwbReading& r : readings) out.push_back({now, std::move(r)});
    } else {
      std::vector<TlvFrame> frames;
      tlv_parser_.Feed(bytes, frames);
      HandleFrames(frames, now, out);
    }
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
