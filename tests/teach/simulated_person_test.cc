// The realistic simulated person at the tabletop's keyboard: it finishes takes as a person does
// (slower than the scripted teacher, with pauses, overshoot and an occasional missed grasp), and
// a take ends where a person ends it (the goal holds, the gripper clear).

#include <gtest/gtest.h>

#include <cstdio>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/pauses.h"
#include "engine/teach/person_takes.h"
#include "engine/teach/simulated_person.h"
#include "engine/worlds/world.h"

namespace recon::teach {
namespace {

std::unique_ptr<worlds::Tabletop> MakeTabletop() {
  return std::make_unique<worlds::Tabletop>(worlds::TabletopOptions{},
                                            std::make_unique<render::MujocoRenderer>());
}

std::vector<uint64_t> Seeds(int n, uint64_t first) {
  std::vector<uint64_t> seeds;
  for (int i = 0; i < n; ++i) seeds.push_back(first + static_cast<uint64_t>(i));
  return seeds;
}

TEST(SimulatedPerson, TeachesLikeAPersonNotLikeTheScript) {
  constexpr uint64_t kPersonSeed = 7;
  std::printf("person seed %llu, scenes 101-108\n", static_cast<unsigned long long>(kPersonSeed));
  auto world = MakeTabletop();
  const std::vector<uint64_t> seeds = Seeds(8, 101);
  PersonTakeStats stats;
  const Dataset person = RecordPersonDemonstrations(*world, seeds, 0, kPersonSeed, {}, 5, &stats);
  const Dataset scripted = worlds::RecordDemonstrations(*world, seeds, 0);
  std::printf(
      "kept %d of %d tries, %d done, %d grasp attempts, %.1f s a take (longest %.1f s), "
      "%.0f %% still\n",
      stats.demonstrations, stats.tries, stats.kept_done, stats.grasp_attempts,
      stats.kept_seconds / stats.demonstrations, stats.longest_kept_seconds,
      100.0 * stats.still_samples / stats.kept_samples);
  ASSERT_EQ(person.demos.size(), seeds.size());
  EXPECT_EQ(stats.demonstrations, 8);
  // Most takes get done, if not always at the first try.
  EXPECT_GE(stats.kept_done, 6);
  EXPECT_GE(stats.tries, stats.demonstrations);
  // A person misses a grasp now and then: more closes than takes.
  EXPECT_GT(stats.grasp_attempts, stats.tries);
  // Slower than the script, with the arm standing still while the person looks and reacts.
  EXPECT_GT(person.NumDemoSamples(), scripted.NumDemoSamples());
  EXPECT_GT(stats.still_samples, stats.kept_samples / 10);
  // Every kept take that is done ends where a person ends it, not at the script's end point.
  for (const Episode& e : person.demos) {
    EXPECT_LE(static_cast<int>(e.samples.size()), world->EpisodeLength());
  }
  // A person's takes are full of pauses, which the recipe leaves out; the scripted teacher's
  // commands that move nothing are its waits for the fingers, far fewer, and its takes are
  // kept whole (WithoutPauses' `of`).
  const std::vector<float> motion = world->ActionNoiseScale();
  int64_t person_pauses = 0, scripted_waits = 0, scripted_dropped = -1;
  WithoutPauses(person, motion, &person_pauses);
  WithoutPauses(scripted, motion, &scripted_waits);
  const Dataset scripted_kept = WithoutPauses(scripted, motion, &scripted_dropped,
                                              std::vector<bool>(scripted.demos.size(), false));
  std::printf(
      "pauses: %lld of %lld person samples, %lld of %lld scripted\n",
      static_cast<long long>(person_pauses), static_cast<long long>(person.NumDemoSamples()),
      static_cast<long long>(scripted_waits), static_cast<long long>(scripted.NumDemoSamples()));
  EXPECT_GT(person_pauses, person.NumDemoSamples() / 5);
  EXPECT_LT(scripted_waits * 5, person_pauses);
  EXPECT_EQ(scripted_dropped, 0);
  EXPECT_EQ(Fingerprint(scripted_kept), Fingerprint(scripted));
}

TEST(SimulatedPerson, TheSameSeedGivesTheSameTakes) {
  auto world = MakeTabletop();
  const std::vector<uint64_t> seeds = Seeds(1, 5);
  const Dataset a = RecordPersonDemonstrations(*world, seeds, 3, 11, {}, 1);
  const Dataset b = RecordPersonDemonstrations(*world, seeds, 3, 11, {}, 1);
  const Dataset c = RecordPersonDemonstrations(*world, seeds, 3, 12, {}, 1);
  EXPECT_EQ(Fingerprint(a), Fingerprint(b));
  EXPECT_NE(Fingerprint(a), Fingerprint(c));
  EXPECT_EQ(a.play.size(), 3u);
}

TEST(GoalHoldsAndClear, OnlyOnceTheToastLiesOnThePlateAndTheGripperIsAway) {
  auto world = MakeTabletop();
  world->Reset(3);
  EXPECT_FALSE(world->GoalHoldsAndClear());
  // The scripted teacher's take passes through the goal holding with the gripper clear before
  // it reaches its own end point: a person's take ends sooner.
  int person_end = -1, script_end = -1;
  for (int t = 0; t < world->EpisodeLength(); ++t) {
    world->Step(world->ExpertAction());
    if (person_end < 0 && world->GoalHoldsAndClear()) {
      person_end = t;
      EXPECT_TRUE(world->TaskSucceeded());
      EXPECT_FALSE(world->arm().GripperClosed());
    }
    if (world->DemonstrationDone()) {
      script_end = t;
      break;
    }
  }
  ASSERT_GE(person_end, 0);
  ASSERT_GE(script_end, 0);
  EXPECT_LT(person_end, script_end);
  EXPECT_TRUE(world->GoalHoldsAndClear());
}

}  // namespace
}  // namespace recon::teach
