// Mutated RTDE byte streams (bit flips, insertions, deletions, truncations, splices) fed in random
// chunks to RtdeStreamReader, and every packet that comes out to the decoders: nothing crashes,
// reads out of bounds (run under ASan too) or hangs; every byte is accounted for; a corrupt
// stream is declared once; and after Reset() (a new connection) valid packets parse again.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "devices/robot/rtde_protocol.h"

namespace recon::robot {
namespace {

constexpr uint64_t kCorpusSeed = 20240611;
constexpr int kMutatedStreams = 100000;

RtdeRecipe Recipe() {
  return {1,
          {"timestamp", "actual_q", "actual_qd", "robot_mode", "safety_mode", "actual_TCP_pose"},
          {RtdeFieldType::kDouble, RtdeFieldType::kVector6d, RtdeFieldType::kVector6d,
           RtdeFieldType::kInt32, RtdeFieldType::kInt32, RtdeFieldType::kVector6d}};
}

/// A plausible session: handshake replies, a text message, then data packages.
std::string ValidStream(std::mt19937_64& rng, int* packets) {
  std::uniform_real_distribution<double> angle(-6.28, 6.28);
  std::string s =
      EncodeAccepted(RtdePacketType::kRequestProtocolVersion, true) +
      EncodeControllerVersion({5, 11, 0, 108}) +
      EncodeSetupOutputsReply(1, {"DOUBLE", "VECTOR6D", "VECTOR6D", "INT32", "INT32", "VECTOR6D"}) +
      EncodeAccepted(RtdePacketType::kStart, true) + EncodeTextMessage({"fuzz", "RTDE", 3});
  *packets = 5;
  const int data = 1 + static_cast<int>(rng() % 5);
  for (int i = 0; i < data; ++i) {
    std::array<double, 6> q, qd, pose;
    for (size_t j = 0; j < 6; ++j) q[j] = angle(rng), qd[j] = angle(rng), pose[j] = angle(rng);
    s += PackDataPackage(Recipe(), {0.008 * i, q, qd, int32_t{7}, int32_t{1}, pose});
    ++*packets;
  }
  return s;
}

std::string Mutate(std::string s, const std::string& other, std::mt19937_64& rng) {
  const int mutations = 1 + static_cast<int>(rng() % 4);
  for (int m = 0; m < mutations; ++m) {
    const size_t at = s.empty() ? 0 : rng() % s.size();
    switch (rng() % 6) {
      case 0:  // bit flip
        if (!s.empty()) s[at] = static_cast<char>(s[at] ^ (1 << (rng() % 8)));
        break;
      case 1:  // insertion of random bytes
        for (size_t n = 1 + rng() % 8; n > 0; --n) {
          s.insert(s.begin() + static_cast<std::ptrdiff_t>(at), static_cast<char>(rng()));
        }
        break;
      case 2:  // deletion
        s.erase(at, 1 + rng() % 16);
        break;
      case 3:  // truncation
        s.resize(at);
        break;
      case 4: {  // splice: the tail of another stream from a random point
        const size_t from = other.empty() ? 0 : rng() % other.size();
        s = s.substr(0, at) + other.substr(from);
        break;
      }
      default:  // overwrite a byte with an extreme value (size fields love 0x00 and 0xFF)
        if (!s.empty()) s[at] = (rng() % 2) ? '\xff' : '\0';
    }
  }
  return s;
}

TEST(RtdeFuzzTest, MutatedStreamsInRandomChunksNeverBreakTheReader) {
  std::printf("RTDE fuzz corpus seed %llu, %d mutated streams\n",
              static_cast<unsigned long long>(kCorpusSeed), kMutatedStreams);
  std::mt19937_64 rng(kCorpusSeed);
  std::vector<std::string> bases;
  std::vector<int> base_packets;
  for (int i = 0; i < 32; ++i) {
    int packets = 0;
    bases.push_back(ValidStream(rng, &packets));
    base_packets.push_back(packets);
  }
  const RtdeRecipe recipe = Recipe();
  int64_t corrupt_streams = 0, unpacked = 0, refused = 0, decoded_text = 0, total_packets = 0;
  std::vector<RtdePacket> packets;
  for (int n = 0; n < kMutatedStreams; ++n) {
    const size_t b = rng() % bases.size();
    const std::string stream = Mutate(bases[b], bases[rng() % bases.size()], rng);
    RtdeStreamReader reader;
    packets.clear();
    size_t at = 0;
    while (at < stream.size()) {
      const size_t chunk = 1 + rng() % 300;
      reader.Feed(stream.data() + at, std::min(chunk, stream.size() - at), packets);
      at += chunk;
    }
    // Every byte is a delivered packet, waiting for the rest of one, or discarded as corrupt.
    int64_t delivered_bytes = 0;
    for (const RtdePacket& p : packets) {
      ASSERT_LE(p.payload.size() + kRtdeHeaderSize, kRtdeMaxPacketSize);
      delivered_bytes += static_cast<int64_t>(p.payload.size() + kRtdeHeaderSize);
      if (p.type == 'U') {
        std::string why;
        if (UnpackDataPackage(recipe, p.payload, &why)) {
          ++unpacked;
        } else {
          ASSERT_FALSE(why.empty());
          ++refused;
        }
      } else if (p.type == 'M') {
        decoded_text += DecodeTextMessage(p.payload).has_value();
      } else if (p.type == 'O') {
        DecodeSetupOutputsReply(p.payload);
      } else if (p.type == 'v') {
        DecodeControllerVersion(p.payload);
      }
    }
    const RtdeStreamStats& stats = reader.stats();
    ASSERT_EQ(stats.bytes, static_cast<int64_t>(stream.size()));
    ASSERT_EQ(stats.packets, static_cast<int64_t>(packets.size()));
    ASSERT_EQ(delivered_bytes + static_cast<int64_t>(reader.pending()) + stats.discarded,
              stats.bytes)
        << "stream " << n;
    if (reader.corrupt()) {
      ++corrupt_streams;
      ASSERT_EQ(stats.errors, 1);
      ASSERT_EQ(reader.pending(), 0u);
      ASSERT_FALSE(reader.error().empty());
    } else {
      ASSERT_EQ(stats.errors, 0);
    }
    total_packets += stats.packets;
    // A new connection: the same reader, reset, reads a clean stream completely.
    if (n % 97 == 0) {
      reader.Reset();
      packets.clear();
      ASSERT_TRUE(reader.Feed(bases[b], packets));
      ASSERT_EQ(static_cast<int>(packets.size()), base_packets[b]);
      ASSERT_TRUE(UnpackDataPackage(recipe, packets.back().payload));
    }
  }
  std::printf(
      "%lld corrupt streams, %lld packets, %lld data packages unpacked, %lld refused, "
      "%lld text messages\n",
      static_cast<long long>(corrupt_streams), static_cast<long long>(total_packets),
      static_cast<long long>(unpacked), static_cast<long long>(refused),
      static_cast<long long>(decoded_text));
  // The mutations must have exercised every path, or the test proves nothing.
  EXPECT_GT(corrupt_streams, kMutatedStreams / 20);
  EXPECT_LT(corrupt_streams, kMutatedStreams);
  EXPECT_GT(unpacked, kMutatedStreams);
  EXPECT_GT(refused, 100);
}

TEST(RtdeFuzzTest, RandomPayloadsNeverReadPastTheEndOfADataPackage) {
  constexpr uint64_t kSeed = 77;
  std::printf("unpacker fuzz seed %llu\n", static_cast<unsigned long long>(kSeed));
  std::mt19937_64 rng(kSeed);
  const RtdeRecipe recipe = Recipe();
  int accepted = 0;
  for (int n = 0; n < 20000; ++n) {
    // Around the right size, so the exact-size path is hit as well as short and long ones.
    const size_t size = 1 + recipe.PayloadSize() - 4 + rng() % 9;
    std::string payload(size, '\0');
    for (char& c : payload) c = static_cast<char>(rng());
    payload[0] = static_cast<char>(rng() % 2);
    const auto values = UnpackDataPackage(recipe, payload);
    if (values) {
      ++accepted;
      ASSERT_EQ(values->size(), recipe.types.size());
      ASSERT_EQ(payload.size(), 1 + recipe.PayloadSize());
    }
    DecodeTextMessage(payload.substr(0, rng() % payload.size()));
    DecodeSetupOutputsReply(payload.substr(0, rng() % 4));
  }
  EXPECT_GT(accepted, 500);
}

}  // namespace
}  // namespace recon::robot
