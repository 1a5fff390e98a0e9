// DWM1001 parsing throughput and the latency from a byte on the wire to a reading
// (issue 6). Targets (bench/report.py): lec parsing >= 100,000 lines/s; pty line to reading
// median <= 2 ms.

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "devices/uwb/lec_parser.h"
#include "devices/uwb/serial_port.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "devices/uwb/tlv_codec.h"

namespace recon::uwb {
namespace {

constexpr int kUpdates = 10000;

std::vector<UwbReading> Readings() {
  SimulatedDwm1001Options options;
  options.seed = 6;
  SimulatedDwm1001 tag(options);
  std::vector<UwbReading> readings;
  for (int i = 0; i < kUpdates; ++i) readings.push_back(tag.NextReading({0.5 + 1e-4 * i, 0.4, 0}));
  return readings;
}

// Four-anchor `lec` lines with a position, as a tag prints them at 10 Hz, fed in 4 KiB reads.
void BM_LecParseLines(benchmark::State& state) {
  std::string stream;
  for (const UwbReading& r : Readings()) stream += FormatLecLine(r);
  std::vector<UwbReading> out;
  out.reserve(kUpdates);
  for (auto _ : state) {
    LecLineParser parser;
    out.clear();
    for (size_t i = 0; i < stream.size(); i += 4096) {
      parser.Feed(std::string_view(stream).substr(i, 4096), out);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["lines_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kUpdates, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LecParseLines)->Unit(benchmark::kMillisecond);

// loc_get responses (status, position, four anchors: 101 bytes, 3 frames), fed in 4 KiB reads.
void BM_TlvParseFrames(benchmark::State& state) {
  std::string stream;
  for (const UwbReading& r : Readings()) {
    stream += EncodeStatus(0) + EncodePosition(r) + EncodeAnchorList(r.anchors);
  }
  std::vector<TlvFrame> out;
  out.reserve(3 * kUpdates);
  int64_t frames = 0;
  for (auto _ : state) {
    TlvResponseParser parser;
    out.clear();
    for (size_t i = 0; i < stream.size(); i += 4096) {
      parser.Feed(std::string_view(stream).substr(i, 4096), out);
    }
    frames += static_cast<int64_t>(out.size());
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TlvParseFrames)->Unit(benchmark::kMillisecond);

// One lec line written to a pseudo-terminal's master, until the SerialPort read on the slave
// and the LecLineParser behind it (what Dwm1001Driver::Poll does) deliver the reading.
void BM_PtyLineToReadingLatency(benchmark::State& state) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) {
    state.SkipWithError("no pseudo-terminals");
    return;
  }
  termios tty{};
  ::tcgetattr(master, &tty);
  ::cfmakeraw(&tty);
  ::tcsetattr(master, TCSANOW, &tty);
  SerialPort port(::ptsname(master));
  LecLineParser parser;
  const std::string line = FormatLecLine(Readings().front());
  std::vector<double> latencies_us;
  std::vector<UwbReading> out;
  std::string bytes;
  for (auto _ : state) {
    out.clear();
    const auto start = std::chrono::steady_clock::now();
    if (::write(master, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
      state.SkipWithError("write failed");
      break;
    }
    while (out.empty()) {
      bytes.clear();
      if (!port.Read(bytes, 100)) {
        state.SkipWithError("the pseudo-terminal hung up");
        break;
      }
      parser.Feed(bytes, out);
    }
    latencies_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
  }
  ::close(master);
  if (latencies_us.empty()) return;
  std::sort(latencies_us.begin(), latencies_us.end());
  state.counters["median_latency_us"] = latencies_us[latencies_us.size() / 2];
  state.counters["p99_latency_us"] = latencies_us[latencies_us.size() * 99 / 100];
}
BENCHMARK(BM_PtyLineToReadingLatency)->Iterations(2000)->UseRealTime();

}  // namespace
}  // namespace recon::uwb

BENCHMARK_MAIN();
