// The DWM1001 TLV codec: request bytes as documented, and the response parser on exact bytes,
// in every chunking, after garbage and with hostile lengths.

#include "devices/uwb/tlv_codec.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/rng.h"

namespace recon::uwb {
namespace {

std::string Bytes(std::initializer_list<int> values) {
  std::string out;
  for (const int v : values) out.push_back(static_cast<char>(v));
  return out;
}

UwbReading SampleReading() {
  UwbReading r;
  r.has_position = true;
  r.x_m = 1.234;
  r.y_m = -0.5;
  r.z_m = 0.007;
  r.quality = 87;
  r.anchors = {{0x0C8A, 0.0, 0.0, 1.2, 2.345}, {0x1D42, 2.4, 0.0, 1.2, 1.001}};
  return r;
}

void CheckAccounting(const TlvResponseParser& parser) {
  const TlvParseStats& s = parser.stats();
  EXPECT_EQ(s.bytes,
            s.frame_bytes + s.dropped_bytes + static_cast<int64_t>(parser.pending_bytes()));
}

TEST(TlvCodecTest, RequestsAreTheDocumentedBytes) {
  EXPECT_EQ(EncodePosGet(), Bytes({0x02, 0x00}));
  EXPECT_EQ(EncodeLocGet(), Bytes({0x0C, 0x00}));
  EXPECT_EQ(EncodeNodeIdGet(), Bytes({0x30, 0x00}));
  EXPECT_EQ(EncodeUpdRateSet(1, 300), Bytes({0x03, 0x04, 0x01, 0x00, 0x2C, 0x01}));
  EXPECT_THROW(EncodeUpdRateSet(0, 1), std::invalid_argument);
  EXPECT_THROW(EncodeUpdRateSet(1, 601), std::invalid_argument);
}

TEST(TlvCodecTest, ResponsesAreLittleEndianMillimetres) {
  UwbReading r;
  r.has_position = true;
  r.x_m = 0.01;
  r.y_m = 78.888;
  r.z_m = -0.334;
  r.quality = 57;
  // The `apg` example of REFERENCE.md, x:10 y:78888 z:-334 qf:57, as TLV.
  EXPECT_EQ(EncodePosition(r),
            Bytes({0x41, 0x0D, 0x0A, 0, 0, 0, 0x28, 0x34, 0x01, 0, 0xB2, 0xFE, 0xFF, 0xFF, 57}));
  EXPECT_EQ(EncodeNodeId(0xDECA0000000012ABull),
            Bytes({0x4A, 0x08, 0xAB, 0x12, 0, 0, 0, 0, 0xCA, 0xDE}));
  EXPECT_EQ(EncodeStatus(1), Bytes({0x40, 0x01, 0x01}));
  const std::string list = EncodeAnchorList(SampleReading().anchors);
  ASSERT_EQ(list.size(), 3u + 2 * 20);
  EXPECT_EQ(list.substr(0, 9), Bytes({0x49, 41, 2, 0x8A, 0x0C, 0x29, 0x09, 0, 0}));  // 2345 mm
  r.quality = 101;
  EXPECT_THROW(EncodePosition(r), std::invalid_argument);
  EXPECT_THROW(EncodeAnchorList(std::vector<AnchorRange>(13)), std::invalid_argument);
}

TEST(TlvCodecTest, ParsesALocGetResponseInEveryChunking) {
  const UwbReading sample = SampleReading();
  const std::string response = EncodeStatus(0) + EncodePosition(sample) +
                               EncodeAnchorList(sample.anchors) + EncodeStatus(3) +
                               EncodeStatus(0) + EncodeNodeId(0x1122334455667788ull);
  for (size_t chunk = 1; chunk <= response.size(); ++chunk) {
    TlvResponseParser parser;
    std::vector<TlvFrame> frames;
    for (size_t i = 0; i < response.size(); i += chunk)
      parser.Feed(response.substr(i, chunk), frames);
    ASSERT_EQ(frames.size(), 6u) << "chunk " << chunk;
    EXPECT_EQ(frames[0].kind, TlvFrame::Kind::kStatus);
    EXPECT_EQ(frames[1].kind, TlvFrame::Kind::kPosition);
    EXPECT_TRUE(frames[1].reading.has_position);
    EXPECT_DOUBLE_EQ(frames[1].reading.x_m, 1.234);
    EXPECT_DOUBLE_EQ(frames[1].reading.y_m, -0.5);
    EXPECT_DOUBLE_EQ(frames[1].reading.z_m, 0.007);
    EXPECT_EQ(frames[1].reading.quality, 87);
    ASSERT_EQ(frames[2].kind, TlvFrame::Kind::kAnchorList);
    EXPECT_EQ(frames[2].reading.anchors, sample.anchors);
    EXPECT_EQ(frames[3].error, 3);
    EXPECT_EQ(frames[5].node_id, 0x1122334455667788ull);
    EXPECT_EQ(parser.stats().frames, 6);
    EXPECT_EQ(parser.stats().readings, 1);
    EXPECT_EQ(parser.stats().status_by_code[3], 1);
    EXPECT_EQ(parser.stats().dropped_bytes, 0);
    CheckAccounting(parser);
  }
}

TEST(TlvCodecTest, ResynchronisesAfterGarbageAndCountsWhatItDropped) {
  const std::string good = EncodeStatus(0) + EncodePosition(SampleReading());
  TlvResponseParser parser;
  std::vector<TlvFrame> frames;
  // Text from a shell, a value frame without its status, a status with an unknown code, and a
  // position frame whose length lies: all dropped, then the good response is found.
  const std::string garbage = "dwm> lec\r\n" + EncodePosition(SampleReading()) +
                              Bytes({0x40, 0x01, 0x09, 0x40, 0x00, 0x41}) + EncodeStatus(0) +
                              Bytes({0x41, 0xFF, 1, 2, 3});
  parser.Feed(garbage + good, frames);
  ASSERT_EQ(frames.size(), 3u);  // the lying status ok, then the good response
  EXPECT_EQ(frames[1].kind, TlvFrame::Kind::kStatus);
  EXPECT_EQ(frames[2].kind, TlvFrame::Kind::kPosition);
  EXPECT_EQ(parser.stats().dropped_bytes, static_cast<int64_t>(garbage.size()) - 3);
  EXPECT_GE(parser.stats().rejected, 2);
  EXPECT_GE(parser.stats().garbage_runs, 2);
  CheckAccounting(parser);
}

TEST(TlvCodecTest, OutOfRangeValuesAndLyingCountsAreRejected) {
  TlvResponseParser parser;
  std::vector<TlvFrame> frames;
  // x = 2^31 - 1 mm is 2147 km: garbled.
  parser.Feed(
      EncodeStatus(0) + Bytes({0x41, 0x0D, 0xFF, 0xFF, 0xFF, 0x7F, 0, 0, 0, 0, 0, 0, 0, 0, 50}),
      frames);
  // quality 200.
  parser.Feed(EncodeStatus(0) + Bytes({0x41, 0x0D, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 200}),
              frames);
  // An anchor list whose count says 5 but whose length holds 1.
  std::string list = EncodeAnchorList({SampleReading().anchors[0]});
  list[2] = 5;
  parser.Feed(EncodeStatus(0) + list, frames);
  for (const TlvFrame& f : frames) EXPECT_EQ(f.kind, TlvFrame::Kind::kStatus);
  EXPECT_EQ(parser.stats().readings, 0);
  EXPECT_GE(parser.stats().rejected, 3);
  CheckAccounting(parser);
}

TEST(TlvCodecTest, TheBufferStaysBoundedOnEndlessGarbage) {
  Rng rng(17);
  TlvResponseParser parser;
  std::vector<TlvFrame> frames;
  std::string noise(1 << 16, '\0');
  for (char& c : noise) c = static_cast<char>(rng.UniformInt(256));
  for (int i = 0; i < 16; ++i) {
    parser.Feed(noise, frames);
    EXPECT_LT(parser.pending_bytes(), tlv::kMaxFrameBytes);
  }
  CheckAccounting(parser);
}

}  // namespace
}  // namespace recon::uwb
