#include "devices/uwb/lec_parser.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/core/rng.h"

namespace recon::uwb {
namespace {

// The example from the PANS API guide (lec and lep), with the firmware's "\r\n" terminator.
constexpr char kGuideLec[] =
    "DIST,4,AN0,1151,5.00,8.00,2.25,6.44,AN1,0CA8,0.00,8.00,2.25,6.50,AN2,111C,5.00,0.00,2.25,3.24,"
    "AN3,1150,0.00,0.00,2.25,3.19,POS,2.55,2.01,1.71,98\r\n";
constexpr char kGuideLep[] = "POS,2.57,2.00,1.67,97\r\n";

struct FeedResult {
  std::vector<UwbReading> readings;
  ParseStats stats;
};

FeedResult FeedWhole(std::string_view bytes) {
  LecLineParser parser;
  FeedResult result;
  parser.Feed(bytes, result.readings);
  result.stats = parser.stats();
  return result;
}

void ExpectStatsEq(const ParseStats& a, const ParseStats& b) {
  EXPECT_EQ(a.lines, b.lines);
  EXPECT_EQ(a.readings, b.readings);
  EXPECT_EQ(a.malformed, b.malformed);
  EXPECT_EQ(a.empty, b.empty);
  EXPECT_EQ(a.resynced, b.resynced);
}

// A value on the firmware's centimetre grid; k / 100.0 is the double nearest to the printed
// decimal, so it round-trips exactly.
double Centimetres(Rng& rng, int64_t max_cm, bool allow_negative = true) {
  const int64_t lo = allow_negative ? -max_cm : 0;
  return static_cast<double>(
             lo + static_cast<int64_t>(rng.UniformInt(static_cast<uint64_t>(max_cm - lo + 1)))) /
         100.0;
}

UwbReading RandomReading(Rng& rng, int max_anchors) {
  UwbReading reading;
  const int n = static_cast<int>(rng.UniformInt(static_cast<uint64_t>(max_anchors + 1)));
  for (int i = 0; i < n; ++i) {
    reading.anchors.push_back({static_cast<uint16_t>(rng.UniformInt(65536)),
                               Centimetres(rng, 99999), Centimetres(rng, 99999),
                               Centimetres(rng, 999), Centimetres(rng, 99999, false)});
  }
  if (rng.Uniform() < 0.7) {
    reading.has_position = true;
    reading.x_m = Centimetres(rng, 99999);
    reading.y_m = Centimetres(rng, 99999);
    reading.z_m = Centimetres(rng, 999);
    reading.quality = static_cast<int>(rng.UniformInt(101));
  }
  return reading;
}

TEST(LecFormatTest, ReproducesTheFirmwareExampleByteForByte) {
  const FeedResult result = FeedWhole(std::string(kGuideLec) + kGuideLep);
  ASSERT_EQ(result.readings.size(), 2u);
  const UwbReading& lec = result.readings[0];
  ASSERT_EQ(lec.anchors.size(), 4u);
  EXPECT_EQ(lec.anchors[1].id, 0x0CA8);
  EXPECT_DOUBLE_EQ(lec.anchors[1].y_m, 8.0);
  EXPECT_DOUBLE_EQ(lec.anchors[3].distance_m, 3.19);
  EXPECT_TRUE(lec.has_position);
  EXPECT_EQ(lec.quality, 98);
  EXPECT_EQ(FormatLecLine(lec), kGuideLec);
  const UwbReading& lep = result.readings[1];
  EXPECT_TRUE(lep.anchors.empty());
  EXPECT_DOUBLE_EQ(lep.z_m, 1.67);
  EXPECT_EQ(FormatLepLine(lep), kGuideLep);
}

TEST(LecFormatTest, PrintsIdsUpperCaseAndNoNegativeZero) {
  UwbReading reading;
  reading.anchors.push_back({0x0c8a, -0.001, -0.05, 12.345, 0.004});
  reading.anchors.push_back({0x1, 1.0, 2.0, 3.0, 4.0});
  EXPECT_EQ(FormatLecLine(reading),
            "DIST,2,AN0,0C8A,0.00,-0.05,12.35,0.00,AN1,0001,1.00,2.00,3.00,4.00\r\n");
  EXPECT_EQ(FormatLecLine(UwbReading{}), "DIST,0\r\n");
}

TEST(LecFormatTest, RejectsReadingsTheFirmwareCouldNotPrint) {
  UwbReading good;
  good.has_position = true;
  good.quality = 50;
  EXPECT_NO_THROW(FormatLecLine(good));

  UwbReading bad = good;
  bad.x_m = std::nan("");
  EXPECT_THROW(FormatLecLine(bad), std::invalid_argument);
  bad = good;
  bad.y_m = 9999.996;  // Would print as 10000.00, which the parser rejects.
  EXPECT_THROW(FormatLepLine(bad), std::invalid_argument);
  bad = good;
  bad.quality = 101;
  EXPECT_THROW(FormatLecLine(bad), std::invalid_argument);
  bad = good;
  bad.anchors.assign(kMaxAnchors + 1, AnchorRange{});
  EXPECT_THROW(FormatLecLine(bad), std::invalid_argument);
  bad = good;
  bad.anchors.push_back({1, 0.0, 0.0, 0.0, -0.5});
  EXPECT_THROW(FormatLecLine(bad), std::invalid_argument);
  EXPECT_THROW(FormatLepLine(UwbReading{}), std::invalid_argument);
}

TEST(LecParserTest, RoundTripsFormattedReadings) {
  std::vector<UwbReading> expected;
  UwbReading no_pos;
  no_pos.anchors.push_back({0xBEEF, -1.25, 0.5, 2.0, 3.75});
  expected.push_back(no_pos);
  expected.push_back(UwbReading{});  // DIST,0: no anchors in range, no fix.
  UwbReading pos_only;
  pos_only.has_position = true;
  pos_only.x_m = -9999.99;
  pos_only.y_m = 9999.99;
  pos_only.quality = 0;
  expected.push_back(pos_only);
  Rng rng(7);
  for (int i = 0; i < 200; ++i) expected.push_back(RandomReading(rng, 4));

  std::string stream;
  for (const UwbReading& r : expected) stream += FormatLecLine(r);
  const FeedResult result = FeedWhole(stream);
  EXPECT_EQ(result.readings, expected);
  EXPECT_EQ(result.stats.lines, static_cast<int64_t>(expected.size()));
  EXPECT_EQ(result.stats.malformed, 0);
  EXPECT_EQ(result.stats.resynced, 0);

  // lep carries only the position.
  UwbReading lep_expected = expected.back();
  lep_expected.anchors.clear();
  if (lep_expected.has_position) {
    const FeedResult lep = FeedWhole(FormatLepLine(lep_expected));
    ASSERT_EQ(lep.readings.size(), 1u);
    EXPECT_EQ(lep.readings[0], lep_expected);
  }
}

TEST(LecParserTest, ByteByByteAndRandomChunksEqualWholeFeeding) {
  Rng rng(11);
  std::string stream = "dwm> lec\r\n";
  for (int i = 0; i < 50; ++i) {
    stream += FormatLecLine(RandomReading(rng, 4));
    if (i % 7 == 0) stream += "lePOS,1.00,2.00,0.50,97\r\n\r\nDIST,2,AN0\r\n";
  }
  const FeedResult whole = FeedWhole(stream);
  ASSERT_GT(whole.readings.size(), 50u);

  LecLineParser bytewise;
  std::vector<UwbReading> bytewise_out;
  for (const char c : stream) bytewise.Feed(std::string_view(&c, 1), bytewise_out);
  EXPECT_EQ(bytewise_out, whole.readings);
  ExpectStatsEq(bytewise.stats(), whole.stats);

  LecLineParser chunked;
  std::vector<UwbReading> chunked_out;
  for (size_t i = 0; i < stream.size();) {
    const size_t n = std::min<size_t>(1 + rng.UniformInt(64), stream.size() - i);
    chunked.Feed(std::string_view(stream).substr(i, n), chunked_out);
    i += n;
  }
  EXPECT_EQ(chunked_out, whole.readings);
  ExpectStatsEq(chunked.stats(), whole.stats);
}

TEST(LecParserTest, ToleratesCrLfAndStrayCarriageReturns) {
  LecLineParser parser;
  std::vector<UwbReading> out;
  parser.Feed("POS,1.00,2.00,3.00,50\r", out);
  EXPECT_TRUE(out.empty());  // Nothing is complete before the '\n'.
  parser.Feed("\nPOS,1.00,2.00,3.00,51\n\rPOS,1.00,2.0\r0,3.00,52\r\r\n", out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].quality, 50);
  EXPECT_EQ(out[1].quality, 51);
  EXPECT_EQ(out[2].quality, 52);
  EXPECT_EQ(parser.stats().lines, 3);
  EXPECT_EQ(parser.stats().empty, 0);  // "\r\n" is one terminator, not a blank line.
}

TEST(LecParserTest, CountsPromptsAndBlankLinesAsEmpty) {
  const FeedResult result = FeedWhole("\n\r\n  \t\ndwm> \r\ndwm>\ndwm> dwm> \ndwm> lec\r\n");
  EXPECT_TRUE(result.readings.empty());
  EXPECT_EQ(result.stats.lines, 7);
  EXPECT_EQ(result.stats.empty, 7);
  EXPECT_EQ(result.stats.malformed, 0);
}

TEST(LecParserTest, RejectsEachMalformedLineWithoutPartialUse) {
  const std::vector<std::string> bad_lines = {
      "DIST,2,AN0,0C8A,1.00,2.00,3.00,4.00",                               // n says 2, one anchor.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00,4.00,AN1,0C8B,1.00,2.00,3.00,4.00",  // n says 1, two.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00",                                    // Missing distance.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00,4.00,5.00",                          // Extra field.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00,4.00,POS,1.00,2.00,3.00",            // POS without qf.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00,4.00,POS,1.00,2.00,3.00,50,7",       // Field after qf.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00,4.00,XYZ,1.00,2.00,3.00,50",         // Not POS.
      "DIST,1,AN1,0C8A,1.00,2.00,3.00,4.00",                               // Label out of sequence.
      "DIST,1,AN00,0C8A,1.00,2.00,3.00,4.00",                              // Label not as printed.
      "DIST,x,AN0,0C8A,1.00,2.00,3.00,4.00",                               // Non-numeric count.
      "DIST,17",                                                           // Count above 16.
      "DIST,-1",                                                           // Negative count.
      "DIST",                                                              // No count.
      "DIST,",                                                             // Empty count.
      "DIST,1,AN0,0G8A,1.00,2.00,3.00,4.00",                               // Bad hex id.
      "DIST,1,AN0,10C8A,1.00,2.00,3.00,4.00",                              // Id of 5 hex digits.
      "DIST,1,AN0,,1.00,2.00,3.00,4.00",                                   // Empty id.
      "DIST,1,AN0,-C8A,1.00,2.00,3.00,4.00",                               // Signed id.
      "DIST,1,AN0,0C8A,1.00,2.00,3.00,-4.00",                              // Negative range.
      "DIST,1,AN0,0C8A,1.00,2.x0,3.00,4.00",                               // Non-numeric value.
      "DIST,1,AN0,0C8A,1.00,nan,3.00,4.00",                                // NaN text.
      "POS,inf,2.00,3.00,50",                                              // Infinity text.
      "POS,NaN,2.00,3.00,50",
      "POS,1e3,2.00,3.00,50",                                          // Exponent.
      "POS,+1.00,2.00,3.00,50",                                        // Explicit plus.
      "POS,1.0,2.00,3.00,50",                                          // Lost a digit.
      "POS,1,2.00,3.00,50",                                            // Lost the decimals.
      "POS,.50,2.00,3.00,50",                                          // No integer part.
      "POS,1.00 ,2.00,3.00,50",                                        // Trailing space.
      "POS,10000.00,2.00,3.00,50",                                     // |coordinate| >= 1e4 m.
      "POS,1.00,2.00,3.00,101",                                        // qf above 100.
      "POS,1.00,2.00,3.00,-1",                                         // qf negative.
      "POS,1.00,2.00,3.00,5x",                                         // qf non-numeric.
      "POS,1.00,2.00,3.00,",                                           // qf missing.
      "POS,1.00,2.00,3.00",                                            // Truncated line.
      "POS,1.00,2.00,3.00,50,",                                        // Trailing comma.
      "DIST,2,AN0,0C8A,1.00,2.00,3.00,4.00,AN1,0C8B,1.00,2.",          // Truncated mid-number.
      "1151[5.00,8.00,2.25]=6.48 le_us=2576 est[2.57,1.98,1.68,100]",  // les, not ours.
      "x:10 y:78888 z:-334 qf:57",                                     // apg, not ours.
  };
  for (const std::string& line : bad_lines) {
    SCOPED_TRACE(line);
    EXPECT_FALSE(ParseLecLine(line).has_value());
    const FeedResult result = FeedWhole(line + "\r\n");
    EXPECT_TRUE(result.readings.empty());
    EXPECT_EQ(result.stats.lines, 1);
    EXPECT_EQ(result.stats.malformed, 1);
    EXPECT_EQ(result.stats.empty, 0);
    EXPECT_EQ(result.stats.resynced, 0);
  }
}

TEST(LecParserTest, ResynchronisesOnEchoFragments) {
  const FeedResult result = FeedWhole(
      "lePOS,1.00,2.00,0.50,97\r\n"
      "dwm> lecDIST,2,AN0,0C8A,1.00,2.00,3.00,4.00,AN1,1151,5.00,8.00,2.25,6.44,POS,2.57,2.00,"
      "1.67,60\r\n");
  ASSERT_EQ(result.readings.size(), 2u);
  EXPECT_EQ(result.stats.resynced, 2);
  EXPECT_EQ(result.stats.malformed, 0);
  EXPECT_TRUE(result.readings[0].has_position);
  EXPECT_EQ(result.readings[0].quality, 97);
  // The whole DIST line is recovered, not just its POS tail.
  ASSERT_EQ(result.readings[1].anchors.size(), 2u);
  EXPECT_EQ(result.readings[1].anchors[1].id, 0x1151);
  EXPECT_EQ(result.readings[1].quality, 60);
}

TEST(LecParserTest, ResyncSkipsABrokenCandidateForALaterValidOne) {
  // Half a DIST line followed by a complete lep line: only the lep line is trusted.
  const FeedResult result = FeedWhole("lecDIST,4,AN0,0C8A,1.00,2.0POS,3.00,4.00,0.50,80\n");
  ASSERT_EQ(result.readings.size(), 1u);
  EXPECT_TRUE(result.readings[0].anchors.empty());
  EXPECT_DOUBLE_EQ(result.readings[0].x_m, 3.0);
  EXPECT_EQ(result.stats.resynced, 1);
}

TEST(LecParserTest, DoesNotSalvageTheTailOfALineThatStartsCleanly) {
  const FeedResult result =
      FeedWhole("DIST,4,AN0,0C8A,1.00,2.00,3.00,4.00,POS,1.00,2.00,0.50,97\n");
  EXPECT_TRUE(result.readings.empty());
  EXPECT_EQ(result.stats.malformed, 1);
  EXPECT_EQ(result.stats.resynced, 0);
}

TEST(LecParserTest, DiscardsOverlongLinesAndRecovers) {
  const std::string lep = "POS,1.00,2.00,0.50,97";
  // Exactly kMaxLineBytes of content is still a line (here a resynchronised one) ...
  const std::string at_limit = std::string(LecLineParser::kMaxLineBytes - lep.size(), 'x') + lep;
  FeedResult result = FeedWhole(at_limit + "\r\n");
  EXPECT_EQ(result.readings.size(), 1u);
  EXPECT_EQ(result.stats.resynced, 1);
  // ... one more byte is not, even though the tail would parse; the next line is unaffected.
  LecLineParser parser;
  std::vector<UwbReading> out;
  const std::string over = "x" + at_limit;
  for (size_t i = 0; i < over.size(); i += 100) parser.Feed(over.substr(i, 100), out);
  parser.Feed(std::string(20000, 'y'), out);  // Still no newline: memory must stay bounded.
  parser.Feed("\r\n" + lep + "\r\n", out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].quality, 97);
  EXPECT_EQ(parser.stats().lines, 2);
  EXPECT_EQ(parser.stats().malformed, 1);
  EXPECT_EQ(parser.stats().readings, 1);
  EXPECT_EQ(parser.stats().resynced, 0);
}

TEST(LecParserTest, FeedAppendsWithoutClearing) {
  LecLineParser parser;
  std::vector<UwbReading> out(1);
  parser.Feed(kGuideLep, out);
  EXPECT_EQ(out.size(), 2u);
}

void ExpectSane(const UwbReading& r) {
  auto ok = [](double v) { return std::isfinite(v) && std::fabs(v) < kMaxAbsCoordinate_m; };
  ASSERT_LE(r.anchors.size(), static_cast<size_t>(kMaxAnchors));
  for (const AnchorRange& a : r.anchors) {
    EXPECT_TRUE(ok(a.x_m) && ok(a.y_m) && ok(a.z_m) && ok(a.distance_m));
    EXPECT_GE(a.distance_m, 0.0);
  }
  EXPECT_TRUE(ok(r.x_m) && ok(r.y_m) && ok(r.z_m));
  EXPECT_GE(r.quality, 0);
  EXPECT_LE(r.quality, kMaxQuality);
  if (!r.has_position) {
    EXPECT_TRUE(r.x_m == 0 && r.y_m == 0 && r.z_m == 0 && r.quality == 0);
  }
  // Whatever was accepted must be printable and parse back to itself.
  std::string line = FormatLecLine(r);
  line.resize(line.size() - 2);
  EXPECT_EQ(ParseLecLine(line), r);
}

TEST(LecParserTest, SurvivesMutationFuzz) {
  constexpr uint64_t kSeed = 0x5EED0DC1ULL;
  std::cout << "mutation fuzz seed: " << kSeed << "\n";
  RecordProperty("seed", std::to_string(kSeed));
  Rng rng(kSeed);
  // Bytes that are likely to make a mutated line still almost parse.
  static constexpr char kInterestingBytes[] = ",.-0123456789ANDISTPOS\r\n \0\xff";
  // Explicit length: the literal contains a NUL.
  constexpr std::string_view kInteresting(kInterestingBytes, sizeof(kInterestingBytes) - 1);
  std::string stream;
  for (int i = 0; i < 20000; ++i) {
    UwbReading source = RandomReading(rng, 5);
    std::string line =
        rng.Uniform() < 0.3 && source.has_position ? FormatLepLine(source) : FormatLecLine(source);
    line.resize(line.size() - 2);
    const int mutations = 1 + static_cast<int>(rng.UniformInt(4));
    for (int m = 0; m < mutations; ++m) {
      const size_t at = rng.UniformInt(line.size() + 1);
      const char byte = rng.Uniform() < 0.5 ? kInteresting[rng.UniformInt(kInteresting.size())]
                                            : static_cast<char>(rng.UniformInt(256));
      switch (rng.UniformInt(4)) {
        case 0:  // Flip.
          if (at < line.size()) line[at] = byte;
          break;
        case 1:  // Insert.
          line.insert(line.begin() + static_cast<std::ptrdiff_t>(at), byte);
          break;
        case 2:  // Delete.
          if (at < line.size()) line.erase(at, 1);
          break;
        default:  // Cut here and splice in a prefix echo, as the firmware does at high rates.
          line = (rng.Uniform() < 0.5 ? "le" : "dwm> lec") + line.substr(at);
          break;
      }
    }
    stream += line + "\r\n";
  }

  LecLineParser parser;
  std::vector<UwbReading> out;
  for (size_t i = 0; i < stream.size();) {
    const size_t n = std::min<size_t>(1 + rng.UniformInt(300), stream.size() - i);
    parser.Feed(std::string_view(stream).substr(i, n), out);
    i += n;
  }
  const ParseStats& s = parser.stats();
  EXPECT_EQ(s.lines, std::count(stream.begin(), stream.end(), '\n'));
  EXPECT_EQ(s.lines, s.readings + s.malformed + s.empty);
  EXPECT_EQ(s.readings, static_cast<int64_t>(out.size()));
  EXPECT_LE(s.resynced, s.readings);
  // The mix must exercise every path, or the checks above prove little.
  EXPECT_GT(s.readings, 1000);
  EXPECT_GT(s.malformed, 1000);
  EXPECT_GT(s.resynced, 100);
  for (const UwbReading& r : out) {
    ExpectSane(r);
    if (HasFailure()) break;
  }
  std::cout << "lines " << s.lines << " readings " << s.readings << " malformed " << s.malformed
            << " empty " << s.empty << " resynced " << s.resynced << "\n";
}

}  // namespace
}  // namespace recon::uwb
