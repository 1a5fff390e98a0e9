// The RTDE wire format: every message round-trips, the stream reader splits packets whatever
// the chunking, and impossible sizes or short payloads are reported, never read past.

#include "devices/robot/rtde_protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace recon::robot {
namespace {

RtdePacket Single(const std::string& bytes) {
  RtdeStreamReader reader;
  std::vector<RtdePacket> packets;
  EXPECT_TRUE(reader.Feed(bytes, packets));
  EXPECT_EQ(packets.size(), 1u);
  return packets.empty() ? RtdePacket{} : packets[0];
}

RtdeRecipe TestRecipe() {
  return {3,
          {"timestamp", "actual_q", "robot_mode", "x3", "u32", "u64", "u8", "flag"},
          {RtdeFieldType::kDouble, RtdeFieldType::kVector6d, RtdeFieldType::kInt32,
           RtdeFieldType::kVector3d, RtdeFieldType::kUint32, RtdeFieldType::kUint64,
           RtdeFieldType::kUint8, RtdeFieldType::kBool}};
}

TEST(RtdeProtocolTest, HeaderIsBigEndianSizeIncludingItselfThenType) {
  const std::string bytes = EncodeRequestProtocolVersion(2);
  ASSERT_EQ(bytes.size(), 5u);
  EXPECT_EQ(bytes, std::string("\x00\x05V\x00\x02", 5));
  EXPECT_EQ(EncodeRtdePacket(RtdePacketType::kStart), std::string("\x00\x03S", 3));
  const RtdePacket p = Single(bytes);
  EXPECT_EQ(p.type, 'V');
  EXPECT_EQ(DecodeRequestProtocolVersion(p.payload), 2);
  EXPECT_EQ(DecodeAccepted(Single(EncodeAccepted(RtdePacketType::kStart, true)).payload), true);
  EXPECT_EQ(DecodeAccepted(Single(EncodeAccepted(RtdePacketType::kPause, false)).payload), false);
  EXPECT_FALSE(DecodeAccepted(""));
  EXPECT_FALSE(DecodeRequestProtocolVersion(std::string("\x02", 1)));
}

TEST(RtdeProtocolTest, ControllerVersionSetupAndTextMessagesRoundTrip) {
  const auto version =
      DecodeControllerVersion(Single(EncodeControllerVersion({5, 11, 2, 108})).payload);
  ASSERT_TRUE(version);
  EXPECT_EQ(version->ToString(), "5.11.2.108");
  EXPECT_FALSE(DecodeControllerVersion(std::string(15, '\0')));

  const RtdePacket setup = Single(EncodeSetupOutputs(125.0, {"timestamp", "actual_q"}));
  EXPECT_EQ(setup.type, 'O');
  EXPECT_EQ(setup.payload.substr(0, 8), std::string("\x40\x5f\x40\x00\x00\x00\x00\x00", 8))
      << "125.0 as a big-endian IEEE754 double";
  const auto request = DecodeSetupOutputs(setup.payload);
  ASSERT_TRUE(request);
  EXPECT_EQ(request->frequency_hz, 125.0);
  EXPECT_EQ(request->names, (std::vector<std::string>{"timestamp", "actual_q"}));

  const auto reply =
      DecodeSetupOutputsReply(Single(EncodeSetupOutputsReply(0, {"DOUBLE", "NOT_FOUND"})).payload);
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->recipe_id, 0);
  EXPECT_EQ(reply->types, (std::vector<std::string>{"DOUBLE", "NOT_FOUND"}));
  EXPECT_FALSE(ParseRtdeFieldType("NOT_FOUND"));
  EXPECT_EQ(ParseRtdeFieldType("VECTOR6D"), RtdeFieldType::kVector6d);

  const auto text = DecodeTextMessage(Single(EncodeTextMessage({"hello", "RTDE", 2})).payload);
  ASSERT_TRUE(text);
  EXPECT_EQ(text->message, "hello");
  EXPECT_EQ(text->source, "RTDE");
  EXPECT_EQ(text->level, 2);
  EXPECT_FALSE(DecodeTextMessage(std::string("\x09hi", 3))) << "length past the payload";
}

TEST(RtdeProtocolTest, DataPackagesRoundTripEveryFieldType) {
  const RtdeRecipe recipe = TestRecipe();
  EXPECT_EQ(recipe.PayloadSize(), 8u + 48 + 4 + 24 + 4 + 8 + 1 + 1);
  const std::vector<RtdeValue> values = {
      12.5,
      std::array<double, 6>{0.1, -0.2, 0.3, -std::numeric_limits<double>::max(), 1e-300, 6},
      int32_t{-7},
      std::array<double, 3>{1, 2, 3},
      uint32_t{0xDEADBEEF},
      uint64_t{0x0123456789ABCDEFull},
      uint8_t{200},
      true};
  const RtdePacket p = Single(PackDataPackage(recipe, values));
  EXPECT_EQ(p.type, 'U');
  EXPECT_EQ(p.payload.size(), 1 + recipe.PayloadSize());
  std::string why;
  const auto unpacked = UnpackDataPackage(recipe, p.payload, &why);
  ASSERT_TRUE(unpacked) << why;
  EXPECT_EQ(*unpacked, values);

  // A wrong recipe id, a short and a long payload are refused with the reason.
  std::string other = p.payload;
  other[0] = 4;
  EXPECT_FALSE(UnpackDataPackage(recipe, other, &why));
  EXPECT_NE(why.find("recipe 4"), std::string::npos) << why;
  EXPECT_FALSE(UnpackDataPackage(recipe, p.payload.substr(0, p.payload.size() - 1), &why));
  EXPECT_FALSE(UnpackDataPackage(recipe, p.payload + "x", &why));
  EXPECT_FALSE(UnpackDataPackage(recipe, "", &why));
  EXPECT_THROW(PackDataPackage(recipe, {1.0}), std::invalid_argument);
}

TEST(RtdeProtocolTest, StreamReaderSplitsPacketsWhateverTheChunking) {
  std::string stream;
  for (int i = 0; i < 20; ++i) {
    stream += EncodeTextMessage({"message " + std::to_string(i), "test", 3});
    stream += EncodeRtdePacket(RtdePacketType::kStart);
  }
  for (size_t chunk : {size_t{1}, size_t{2}, size_t{3}, size_t{7}, size_t{64}, stream.size()}) {
    RtdeStreamReader reader;
    std::vector<RtdePacket> packets;
    for (size_t at = 0; at < stream.size(); at += chunk) {
      ASSERT_TRUE(reader.Feed(stream.substr(at, chunk), packets));
    }
    ASSERT_EQ(packets.size(), 40u) << "chunk " << chunk;
    EXPECT_EQ(DecodeTextMessage(packets[38].payload)->message, "message 19");
    EXPECT_EQ(reader.stats().packets, 40);
    EXPECT_EQ(reader.stats().errors, 0);
    EXPECT_EQ(reader.pending(), 0u);
  }
}

TEST(RtdeProtocolTest, AnImpossibleSizeMarksTheStreamCorruptUntilReset) {
  for (const std::string& bad : {std::string("\x00\x02S", 3), std::string("\x00\x00", 2) + "x",
                                 std::string("\xff\xffU", 3)}) {
    RtdeStreamReader reader;
    std::vector<RtdePacket> packets;
    EXPECT_FALSE(reader.Feed(EncodeRtdePacket(RtdePacketType::kPause) + bad, packets));
    EXPECT_EQ(packets.size(), 1u) << "the packet before the damage is delivered";
    EXPECT_TRUE(reader.corrupt());
    EXPECT_EQ(reader.stats().errors, 1);
    EXPECT_NE(reader.error().find("packet size"), std::string::npos) << reader.error();
    EXPECT_FALSE(reader.Feed(EncodeRtdePacket(RtdePacketType::kPause), packets));
    EXPECT_EQ(packets.size(), 1u) << "nothing after the damage can be trusted";
    EXPECT_EQ(reader.stats().errors, 1) << "one error per corruption";
    reader.Reset();
    EXPECT_TRUE(reader.Feed(EncodeRtdePacket(RtdePacketType::kPause), packets));
    EXPECT_EQ(packets.size(), 2u);
  }
  EXPECT_THROW(EncodeRtdePacket('U', std::string(kRtdeMaxPacketSize, 'x')), std::length_error);
}

}  // namespace
}  // namespace recon::robot
