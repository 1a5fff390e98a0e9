// The read-out on recorded frames (a real cell's session): episodes of frames with their beacon
// readings, sampled evenly, filed under the object each beacon marks, and read out of a
// subject's features on whole episodes held out; an object that never moved has no score.

#include "engine/probe/recorded_readout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::probe {
namespace {

using ::testing::HasSubstr;

/// Episodes of `per_episode` frames, the plate at one place per episode (its beacon reading
/// that place plus 1 cm noise), a second beacon on the (unmoved) toast. y carries the plate's
/// place in its first two values, an unrelated number in the third, and in the last ten the
/// episode's number, one-hot (the same over its frames, unrelated to the place).
Dataset Recorded(int demos, int play_chunks, int per_episode) {
  Dataset data;
  Rng rng(5);
  std::vector<float> code(10);
  int episode = 0;
  const auto frame = [&](double px, double py) {
    PlaySample s;
    s.x = {0.0f};
    s.y = {static_cast<float>(px), static_cast<float>(py), static_cast<float>(rng.Uniform(0, 1))};
    s.y.insert(s.y.end(), code.begin(), code.end());
    const double bx = px + 0.01 * rng.Normal(), by = py + 0.01 * rng.Normal();
    s.b = {static_cast<float>(bx), static_cast<float>(by), 0.3f, 0.0f};
    return s;
  };
  for (int e = 0; e < demos; ++e) {
    const double px = rng.Uniform(0.3, 0.8), py = rng.Uniform(-0.4, 0.4);
    std::fill(code.begin(), code.end(), 0.0f);
    code[static_cast<size_t>(episode++ % 10)] = 1.0f;
    Episode demo;
    for (int t = 0; t < per_episode; ++t) {
      const PlaySample s = frame(px, py);
      demo.samples.push_back({s.x, s.y, s.b, {0.0f}});
    }
    data.demos.push_back(demo);
  }
  for (int c = 0; c < play_chunks; ++c) {
    const double px = rng.Uniform(0.3, 0.8), py = rng.Uniform(-0.4, 0.4);
    std::fill(code.begin(), code.end(), 0.0f);
    code[static_cast<size_t>(episode++ % 10)] = 1.0f;
    for (int t = 0; t < per_episode; ++t) data.play.push_back(frame(px, py));
    data.play_chunks.push_back(per_episode);
  }
  return data;
}

const std::vector<BeaconSpec> kBeacons = {{"b1", "the plate", "position", 2, "m"},
                                          {"b2", "the toast", "position", 2, "m"}};

/// Features: the values of y at `at`.
ProbeSubject Sees(const std::vector<size_t>& at) {
  ProbeSubject subject;
  subject.method = subject.label = "sees";
  subject.features = [at](const ProbeSubject::Rows&, const ProbeSubject::Rows& ys) {
    ProbeSubject::Rows out;
    for (const auto& y : ys) {
      out.emplace_back();
      for (size_t i : at) out.back().push_back(y[i]);
    }
    return out;
  };
  return subject;
}

TEST(RecordedReadoutTest, FeaturesThatAreTheBeaconsPlaceReadOutNearOneOnHeldOutEpisodes) {
  const RecordedFrames frames =
      SampleRecordedFrames(Recorded(4, 6, 20), kBeacons, {"plate", "toast"}, 2000);
  EXPECT_EQ(frames.xs.size(), 10u * 20u);
  EXPECT_EQ(frames.episode_count, 10);
  EXPECT_EQ(frames.episodes.front(), 0);
  EXPECT_EQ(frames.episodes.back(), 9);
  ASSERT_EQ(frames.readings.at("plate").size(), frames.xs.size());

  const auto scores = ReadOutRecorded(Sees({0, 1, 2}), frames);  // the place, and noise
  ASSERT_TRUE(scores.at("plate").has_value());
  EXPECT_GT(scores.at("plate")->r2, 0.95);       // only the beacon's 1 cm noise is left
  EXPECT_EQ(scores.at("plate")->held_out, 200);  // every frame predicted, by the other episodes
  EXPECT_FALSE(scores.at("toast").has_value());  // it never moved: nothing to read out

  const auto blind = ReadOutRecorded(Sees({2}), frames);  // only the unrelated number
  ASSERT_TRUE(blind.at("plate").has_value());
  EXPECT_LT(blind.at("plate")->r2, 0.2);
  // Features that only tell the episodes apart know nothing of the place: held out whole, the
  // episodes say so. Held out frame by frame, the same features would look perfect.
  const auto episode_code = ReadOutRecorded(Sees({3, 4, 5, 6, 7, 8, 9, 10, 11, 12}), frames);
  ASSERT_TRUE(episode_code.at("plate").has_value());
  EXPECT_LT(episode_code.at("plate")->r2, 0.2);
  const ProbeSubject code = Sees({3, 4, 5, 6, 7, 8, 9, 10, 11, 12});
  const ReadoutScore leaky = CrossValidatedReadout(code.features(frames.xs, frames.ys),
                                                   frames.readings.at("plate"), {}, 4, 0);
  EXPECT_GT(leaky.r2, 0.9);
}

TEST(RecordedReadoutTest, SamplesEvenlyUpToTheCapAndRefusesAMismatch) {
  const Dataset data = Recorded(2, 6, 100);
  const RecordedFrames frames = SampleRecordedFrames(data, kBeacons, {"plate", "toast"}, 200);
  EXPECT_EQ(frames.xs.size(), 200u);
  EXPECT_EQ(frames.episodes.front(), 0);
  EXPECT_EQ(frames.episodes.back(), 7);  // the last play chunk is reached
  // A play sample of no known chunk stands alone.
  Dataset loose = data;
  loose.play_chunks.clear();
  EXPECT_EQ(SampleRecordedFrames(loose, kBeacons, {"plate", "toast"}, 2000).episode_count, 2 + 600);
  // One episode cannot be held out and fitted on at once: no score rather than a made-up one.
  const RecordedFrames one =
      SampleRecordedFrames(Recorded(1, 0, 30), kBeacons, {"plate", "toast"}, 2000);
  EXPECT_FALSE(ReadOutRecorded(Sees({0, 1}), one).at("plate").has_value());
  try {
    SampleRecordedFrames(data, kBeacons, {"plate"}, 10);
    ADD_FAILURE() << "accepted one object for two beacons";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("2 beacons"));
  }
  const std::vector<BeaconSpec> wide = {{"b1", "the plate", "position", 3, "m"}};
  EXPECT_THROW(SampleRecordedFrames(data, wide, {"plate"}, 10), UserError);
}

}  // namespace
}  // namespace recon::probe
