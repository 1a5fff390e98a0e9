// Seeded mutation fuzzing of both DWM1001 parsers: valid lec/lep/les lines, TLV responses and
// shell noise, mutated (flips, insertions, deletions, truncations, splices) and fed in random
// chunks. Checks: no crash, the stats invariants, every value within the validated ranges, and
// valid data spliced after garbage still recovered. Seeds are printed; RECON_FUZZ_SEED and
// RECON_FUZZ_INPUTS override them (e.g. for a longer run under the sanitizers).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "devices/uwb/lec_format.h"
#include "devices/uwb/lec_parser.h"
#include "devices/uwb/tlv_codec.h"
#include "engine/core/rng.h"

namespace recon::uwb {
namespace {

uint64_t EnvOr(const char* name, uint64_t fallback) {
  const char* value = std::getenv(name);
  return value ? std::strtoull(value, nullptr, 0) : fallback;
}

uint64_t Seed(uint64_t fallback) { return EnvOr("RECON_FUZZ_SEED", fallback); }
int64_t Inputs() { return static_cast<int64_t>(EnvOr("RECON_FUZZ_INPUTS", 120000)); }

double Metres(Rng& rng, double range) { return std::round(rng.Uniform(-range, range) * 100) / 100; }

UwbReading RandomReading(Rng& rng, int max_anchors) {
  UwbReading r;
  const int anchors = static_cast<int>(rng.UniformInt(static_cast<uint64_t>(max_anchors) + 1));
  for (int i = 0; i < anchors; ++i) {
    r.anchors.push_back({static_cast<uint16_t>(rng.UniformInt(65536)), Metres(rng, 50),
                         Metres(rng, 50), Metres(rng, 5), std::fabs(Metres(rng, 80))});
  }
  r.has_position = rng.Uniform() < 0.8;
  if (r.has_position) {
    r.x_m = Metres(rng, 50);
    r.y_m = Metres(rng, 50);
    r.z_m = Metres(rng, 5);
    r.quality = static_cast<int>(rng.UniformInt(101));
  }
  return r;
}

const std::vector<std::string>& ShellNoise() {
  static const std::vector<std::string> noise = {
      "dwm> ",
      "dwm> lec\r\n",
      "lec\r\n",
      "\r\nDWM1001 TWR Real Time Location System\r\n\r\ndwm> ",
      "[000012.345 INF] uwb0: panid=x1234 addr=xDECA0000000012AB\r\n",
      "unknown command\r\n",
      "x:10 y:78888 z:-334 qf:57\r\n",
      "1151[5.00,8.00,2.25]=6.48 0CA8[0.00,8.00,2.25]=6.51 est[2.57,1.98,1.68,100]\r\n",
      std::string("\x40\x01\x00\x41\x0d", 5)};
  return noise;
}

/// One valid piece of the text stream.
std::string LecSample(Rng& rng) {
  const double pick = rng.Uniform();
  if (pick < 0.15) return ShellNoise()[rng.UniformInt(ShellNoise().size())];
  UwbReading r = RandomReading(rng, 6);
  if (pick < 0.35 && r.has_position) return FormatLepLine(r);
  return FormatLecLine(r);
}

/// One valid TLV response (or, rarely, shell text the tag printed before leaving the shell).
std::string TlvSample(Rng& rng) {
  const double pick = rng.Uniform();
  if (pick < 0.05) return ShellNoise()[rng.UniformInt(ShellNoise().size())];
  if (pick < 0.15) return EncodeStatus(1 + static_cast<int>(rng.UniformInt(5)));
  if (pick < 0.25) return EncodeStatus(0) + EncodeNodeId(rng.Next());
  if (pick < 0.35) return EncodeStatus(0);
  UwbReading r = RandomReading(rng, tlv::kMaxListedAnchors);
  r.has_position = true;
  std::string out = EncodeStatus(0) + EncodePosition(r);
  if (pick < 0.9) out += EncodeAnchorList(r.anchors);
  return out;
}

void Mutate(Rng& rng, std::string& bytes, const std::string& donor) {
  static constexpr char kInterestingBytes[] = ",.-0123456789ANDISTPOS\r\n \0\xff\x40\x41\x49\x4a";
  const std::string_view interesting(kInterestingBytes, sizeof(kInterestingBytes) - 1);
  const size_t at = rng.UniformInt(bytes.size() + 1);
  const char byte = rng.Uniform() < 0.5 ? interesting[rng.UniformInt(interesting.size())]
                                        : static_cast<char>(rng.UniformInt(256));
  switch (rng.UniformInt(6)) {
    case 0:  // flip a bit
      if (at < bytes.size()) bytes[at] ^= static_cast<char>(1 << rng.UniformInt(8));
      break;
    case 1:  // insert
      bytes.insert(at, rng.UniformInt(4) + 1, byte);
      break;
    case 2:  // delete a run
      if (at < bytes.size()) bytes.erase(at, 1 + rng.UniformInt(8));
      break;
    case 3:  // truncate
      bytes.resize(at);
      break;
    case 4:  // splice: our prefix, the donor's suffix
      bytes = bytes.substr(0, at) + donor.substr(rng.UniformInt(donor.size() + 1));
      break;
    default:  // replace a byte
      if (at < bytes.size()) bytes[at] = byte;
  }
}

/// Feeds `bytes` to `feed` in random chunks (1 byte to all of it).
template <typename Feed>
void FeedChunked(Rng& rng, std::string_view bytes, Feed feed) {
  const size_t max_chunk = rng.Uniform() < 0.3 ? 1 + rng.UniformInt(4) : 1 + rng.UniformInt(512);
  while (!bytes.empty()) {
    const size_t n = std::min(bytes.size(), 1 + rng.UniformInt(max_chunk));
    feed(bytes.substr(0, n));
    bytes.remove_prefix(n);
  }
}

bool InRange(double v) { return std::isfinite(v) && std::fabs(v) < kMaxAbsCoordinate_m; }

void ExpectValid(const UwbReading& r, size_t max_anchors) {
  ASSERT_LE(r.anchors.size(), max_anchors);
  for (const AnchorRange& a : r.anchors) {
    ASSERT_TRUE(InRange(a.x_m) && InRange(a.y_m) && InRange(a.z_m) && InRange(a.distance_m));
    ASSERT_GE(a.distance_m, 0.0);
  }
  ASSERT_TRUE(InRange(r.x_m) && InRange(r.y_m) && InRange(r.z_m));
  ASSERT_GE(r.quality, 0);
  ASSERT_LE(r.quality, kMaxQuality);
  if (!r.has_position) {
    ASSERT_TRUE(r.x_m == 0 && r.y_m == 0 && r.z_m == 0 && r.quality == 0);
  }
}

TEST(UwbFuzzTest, LecLineParserSurvivesMutatedStreams) {
  const uint64_t seed = Seed(0x1EC5EED);
  std::cout << "lec fuzz seed: " << seed << " inputs: " << Inputs() << "\n";
  RecordProperty("seed", std::to_string(seed));
  Rng rng(seed);
  int64_t spliced = 0, recovered = 0, spliced_after_newline = 0;
  int64_t total_lines = 0, total_readings = 0, total_resynced = 0;
  for (int64_t input = 0; input < Inputs(); ++input) {
    std::string bytes;
    const int pieces = 1 + static_cast<int>(rng.UniformInt(4));
    for (int p = 0; p < pieces; ++p) bytes += LecSample(rng);
    const std::string donor = LecSample(rng);
    const int mutations = static_cast<int>(rng.UniformInt(5));
    for (int m = 0; m < mutations; ++m) Mutate(rng, bytes, donor);
    // Half the inputs end with a valid line glued on: right after the garbage (as an interleaved
    // echo), or after a line break. Either way it must come out exactly.
    std::optional<UwbReading> expected;
    bool after_newline = false;
    if (rng.Uniform() < 0.5) {
      UwbReading r = RandomReading(rng, 6);
      after_newline = rng.Uniform() < 0.5;
      bytes += (after_newline ? "\r\n" : "") + FormatLecLine(r);
      expected = r;
    }
    LecLineParser parser;
    std::vector<UwbReading> out;
    FeedChunked(rng, bytes, [&](std::string_view chunk) { parser.Feed(chunk, out); });
    const ParseStats& s = parser.stats();
    ASSERT_EQ(s.lines, s.readings + s.malformed + s.empty) << "input " << input;
    ASSERT_EQ(s.readings, static_cast<int64_t>(out.size()));
    ASSERT_LE(s.resynced, s.readings);
    for (const UwbReading& r : out) ExpectValid(r, kMaxAnchors);
    total_lines += s.lines;
    total_readings += s.readings;
    total_resynced += s.resynced;
    if (expected) {
      ++spliced;
      const bool got = !out.empty() && out.back() == *expected;
      recovered += got;
      if (after_newline) {
        ++spliced_after_newline;
        ASSERT_TRUE(got) << "input " << input << ": a valid line after a line break was lost";
      }
    }
  }
  std::cout << "lec: " << total_lines << " lines, " << total_readings << " readings, "
            << total_resynced << " resynchronised; valid lines spliced after garbage: " << recovered
            << " of " << spliced << " recovered (" << spliced_after_newline
            << " after a line break, all recovered)\n";
  EXPECT_GT(total_resynced, 1000);
  // Glued straight onto garbage, a line is lost when the garbage after the last line break
  // starts cleanly with "DIST," or "POS,": by design the parser never searches such a line for a
  // later start (that would salvage the tail of a broken line). The rest must come out.
  EXPECT_GT(recovered, spliced * 3 / 4);
}

TEST(UwbFuzzTest, TlvResponseParserSurvivesMutatedStreams) {
  const uint64_t seed = Seed(0x7115EED);
  std::cout << "tlv fuzz seed: " << seed << " inputs: " << Inputs() << "\n";
  RecordProperty("seed", std::to_string(seed));
  Rng rng(seed);
  int64_t spliced = 0, recovered = 0, spliced_clean = 0, total_dropped = 0, total_frames = 0;
  for (int64_t input = 0; input < Inputs(); ++input) {
    std::string bytes;
    const int pieces = 1 + static_cast<int>(rng.UniformInt(4));
    for (int p = 0; p < pieces; ++p) bytes += TlvSample(rng);
    const std::string donor = TlvSample(rng);
    const int mutations = static_cast<int>(rng.UniformInt(5));
    for (int m = 0; m < mutations; ++m) Mutate(rng, bytes, donor);
    TlvResponseParser parser;
    std::vector<TlvFrame> out;
    FeedChunked(rng, bytes, [&](std::string_view chunk) { parser.Feed(chunk, out); });
    // Then, half the time, a valid loc_get response after the garbage.
    UwbReading expected = RandomReading(rng, 4);
    expected.has_position = true;
    const bool splice = rng.Uniform() < 0.5;
    const bool clean = parser.pending_bytes() == 0;  // no frame in progress at the boundary
    const size_t before = out.size();
    if (splice) {
      // The valid response, then what the tag sends next (error statuses here, which cannot
      // be mistaken for it): a frame in progress at the boundary swallows the response until
      // enough bytes arrive to reject it, after which the parser rescans what it held.
      std::string valid =
          EncodeStatus(0) + EncodePosition(expected) + EncodeAnchorList(expected.anchors);
      for (size_t i = 0; i < tlv::kMaxFrameBytes / 3 + 1; ++i) valid += EncodeStatus(4);
      FeedChunked(rng, valid, [&](std::string_view chunk) { parser.Feed(chunk, out); });
    }
    const TlvParseStats& s = parser.stats();
    ASSERT_EQ(s.bytes,
              s.frame_bytes + s.dropped_bytes + static_cast<int64_t>(parser.pending_bytes()))
        << "input " << input;
    ASSERT_LT(parser.pending_bytes(), tlv::kMaxFrameBytes);
    ASSERT_EQ(s.frames, static_cast<int64_t>(out.size()));
    int64_t statuses = 0, positions = 0;
    for (const TlvFrame& f : out) {
      ExpectValid(f.reading, tlv::kMaxListedAnchors);
      if (f.kind == TlvFrame::Kind::kStatus) {
        ++statuses;
        ASSERT_LT(f.error, tlv::kErrorCodes);
      }
      positions += f.kind == TlvFrame::Kind::kPosition;
    }
    int64_t by_code = 0;
    for (const int64_t n : s.status_by_code) by_code += n;
    ASSERT_EQ(by_code, statuses);
    ASSERT_EQ(s.readings, positions);
    total_dropped += s.dropped_bytes;
    total_frames += s.frames;
    if (splice) {
      ++spliced;
      bool got = false;
      for (size_t i = before; i + 2 < out.size() && !got; ++i) {
        got = out[i].kind == TlvFrame::Kind::kStatus && out[i].error == 0 &&
              out[i + 1].kind == TlvFrame::Kind::kPosition &&
              out[i + 1].reading.x_m == expected.x_m &&
              out[i + 1].reading.quality == expected.quality &&
              out[i + 2].kind == TlvFrame::Kind::kAnchorList &&
              out[i + 2].reading.anchors == expected.anchors;
      }
      recovered += got;
      if (clean) {
        ++spliced_clean;
        ASSERT_TRUE(got) << "input " << input << ": a response after resynchronising was lost";
      }
    }
  }
  std::cout << "tlv: " << total_frames << " frames, " << total_dropped
            << " bytes dropped; valid responses spliced after garbage: " << recovered << " of "
            << spliced << " recovered (" << spliced_clean
            << " with no frame in progress, all recovered)\n";
  EXPECT_GT(total_dropped, 100000);
  // With a frame in progress, the response is lost only if the garbage and the response
  // together happen to form a frame that passes every length and range check (a node id, which
  // has no range, swallowing the start of the response).
  EXPECT_GT(recovered, spliced * 97 / 100);
}

}  // namespace
}  // namespace recon::uwb
