// SimulatedBeaconSource on the tabletop scene without a renderer: the 10 Hz schedule, positions
// through the hidden frame, garbled lines, several beacons, unknown sites.

#include "devices/sim/simulated_beacon_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <map>
#include <regex>
#include <set>

#include "devices/sim/hidden_uwb_frame.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/worlds/scene_assets.h"

namespace recon::sim {
namespace {

using ::testing::HasSubstr;

Eigen::Vector3d SitePosition(const worlds::MujocoModel& scene, const char* site) {
  const int id = mj_name2id(scene.model(), mjOBJ_SITE, site);
  const mjtNum* p = scene.data()->site_xpos + 3 * id;
  return {p[0], p[1], p[2]};
}

worlds::MujocoModel TabletopScene() {
  worlds::MujocoModel scene = worlds::LoadScene("tabletop");
  mj_forward(scene.model(), scene.data());
  return scene;
}

SimulatedBeacon PlateBeacon(uint64_t seed) {
  SimulatedBeacon beacon{"plate", "beacon", {}};
  Rng frame_rng(seed);
  beacon.dwm.table_to_uwb = DrawHiddenUwbFrame(frame_rng);
  beacon.dwm.seed = seed;
  return beacon;
}

TEST(SimulatedBeaconSourceTest, TenUpdatesASecondThroughTheHiddenFrame) {
  const worlds::MujocoModel scene = TabletopScene();
  devices::ManualClock clock;
  const SimulatedBeacon plate = PlateBeacon(21);  // seed 21: hidden frame and noise
  const calib::RigidTransform uwb_to_table = Inverse(plate.dwm.table_to_uwb);
  SimulatedBeaconSource source(scene, {plate}, clock);
  EXPECT_EQ(source.Describe(), "simulated DWM1001 beacons: plate at site 'beacon'");
  EXPECT_TRUE(source.Poll().empty()) << "no update is due at the start";

  const Eigen::Vector3d truth = SitePosition(scene, "beacon");
  constexpr int kSteps = 300;  // 30 s
  std::vector<devices::BeaconSample> samples;
  for (int step = 1; step <= kSteps; ++step) {
    clock.Advance(0.1);
    const std::vector<devices::BeaconSample> polled = source.Poll();
    EXPECT_LE(polled.size(), 1u) << "one update per 0.1 s step";
    for (const auto& s : polled) {
      EXPECT_NEAR(s.timestamp_s, 0.1 * step, 1e-9) << "stamped at its update's time";
      samples.push_back(s);
    }
  }
  // 300 updates, 2% dropped and about half of the 3% garbled ones cut: ~290 (s.d. ~3).
  EXPECT_GE(samples.size(), 275u);
  EXPECT_LE(samples.size(), 300u);
  const devices::BeaconSourceStats stats = source.Stats();
  EXPECT_LE(stats.lines, kSteps);
  EXPECT_GE(stats.lines, 285);
  EXPECT_EQ(stats.readings + stats.malformed, stats.lines);
  // Every reading is a sample, except a rare cut line that ends just before its POS.
  EXPECT_GE(stats.readings, static_cast<int64_t>(samples.size()));
  EXPECT_LE(stats.readings, static_cast<int64_t>(samples.size()) + 2);

  Eigen::Vector3d mean_error = Eigen::Vector3d::Zero();
  for (const auto& s : samples) {
    EXPECT_EQ(s.beacon, "plate");
    EXPECT_GE(s.quality, 0);
    EXPECT_LE(s.quality, 100);
    // In the UWB frame the beacon is far from its table position; mapped back it is within the
    // 7 cm per axis noise (0.3 m is over 4 sigma in the plane).
    const Eigen::Vector3d table = uwb_to_table.Apply(s.position_uwb_m);
    EXPECT_LT((table - truth).head<2>().norm(), 0.3);
    EXPECT_GT((s.position_uwb_m - truth).norm(), 0.5);
    mean_error += (table - truth) / static_cast<double>(samples.size());
  }
  EXPECT_LT(mean_error.norm(), 0.03) << "no bias: " << mean_error.transpose();
}

TEST(SimulatedBeaconSourceTest, CatchesUpMissedUpdatesAndSkipsAnOverflowedBacklog) {
  const worlds::MujocoModel scene = TabletopScene();
  devices::ManualClock clock;
  clock.Set(5.0);  // updates are due from the source's start, not from zero
  SimulatedBeacon plate = PlateBeacon(22);
  plate.dwm.drop_probability = plate.dwm.garble_probability = 0.0;
  SimulatedBeaconSource source(scene, {plate}, clock);

  clock.Advance(1.0);
  std::vector<devices::BeaconSample> samples = source.Poll();
  ASSERT_EQ(samples.size(), 10u);
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(samples[k].timestamp_s, 5.1 + 0.1 * k, 1e-9);
  EXPECT_TRUE(source.Poll().empty()) << "each update is printed once";
  clock.Advance(0.05);
  EXPECT_TRUE(source.Poll().empty()) << "half a period is not an update";
  clock.Advance(0.05);
  EXPECT_EQ(source.Poll().size(), 1u);

  clock.Advance(60.0);  // a 10 minute pause would be the same
  samples = source.Poll();
  ASSERT_EQ(samples.size(), static_cast<size_t>(SimulatedBeaconSource::kMaxBacklogUpdates));
  EXPECT_NEAR(samples.back().timestamp_s, 66.1, 1e-9);
  EXPECT_NEAR(samples.front().timestamp_s, 66.1 - 9.9, 1e-9);
}

// Every update garbled, and a twin SimulatedDwm1001 with the same seed shows which bytes each
// update printed. Echo fragments ("le" glued in front) are recovered by resynchronisation; a cut
// line is malformed unless the cut happened to leave a valid line: a DIST line that ends exactly
// before its POS (no position, so no sample), or a POS whose quality lost a trailing digit (the
// position is whole; only the quality is off). No cut line ever gives a sample with a made-up
// position.
TEST(SimulatedBeaconSourceTest, GarbledLinesAreMalformedAndNeverGiveASample) {
  const worlds::MujocoModel scene = TabletopScene();
  const Eigen::Vector3d truth = SitePosition(scene, "beacon");
  devices::ManualClock clock;
  SimulatedBeacon plate = PlateBeacon(23);
  plate.dwm.drop_probability = 0.0;
  plate.dwm.garble_probability = 1.0;
  uwb::SimulatedDwm1001 twin(plate.dwm);
  SimulatedBeaconSource source(scene, {plate}, clock);

  const std::string metres = R"(,-?\d+\.\d\d)";
  const std::string anchor = ",AN\\d,[0-9A-F]{4}" + metres + metres + metres + metres;
  const std::string anchors = "DIST,4(" + anchor + "){4}";
  const std::regex cut_before_pos(anchors + "\r\n");
  const std::regex cut_in_quality(anchors + ",POS" + metres + metres + metres + R"(,\d{1,2}\r\n)");

  constexpr int kUpdates = 400;
  std::map<int, std::string> printed;  // update number -> bytes
  for (int k = 1; k <= kUpdates; ++k) printed[k] = twin.NextUpdate(truth);
  std::vector<devices::BeaconSample> samples;
  for (int k = 1; k <= kUpdates; ++k) {
    clock.Advance(0.1);
    for (auto& s : source.Poll()) samples.push_back(s);
  }

  int echoes = 0, cuts = 0, valid_cuts_without_position = 0, cuts_keeping_position = 0;
  std::set<int> expected_sample_updates;
  for (const auto& [k, bytes] : printed) {
    if (bytes.rfind("le", 0) == 0) {
      ++echoes;
      expected_sample_updates.insert(k);
    } else {
      ++cuts;
      if (std::regex_match(bytes, cut_before_pos)) ++valid_cuts_without_position;
      if (std::regex_match(bytes, cut_in_quality)) {
        ++cuts_keeping_position;
        expected_sample_updates.insert(k);
      }
    }
  }
  ASSERT_GT(echoes, 150);
  ASSERT_GT(cuts, 150);

  const devices::BeaconSourceStats stats = source.Stats();
  EXPECT_EQ(stats.lines, kUpdates);
  EXPECT_EQ(stats.malformed, cuts - valid_cuts_without_position - cuts_keeping_position);
  std::set<int> sample_updates;
  for (const auto& s : samples) {
    const int k = static_cast<int>(std::lround(s.timestamp_s / 0.1));
    sample_updates.insert(k);
    // The sample's position is exactly what the tag printed in full.
    char pos[96];
    std::snprintf(pos, sizeof(pos), "POS,%.2f,%.2f,%.2f,", s.position_uwb_m.x(),
                  s.position_uwb_m.y(), s.position_uwb_m.z());
    EXPECT_THAT(printed[k], HasSubstr(pos)) << "update " << k;
  }
  EXPECT_EQ(samples.size(), sample_updates.size()) << "one sample per update";
  EXPECT_EQ(sample_updates, expected_sample_updates);
}

TEST(SimulatedBeaconSourceTest, SeveralBeaconsEachWithItsOwnTagAndParser) {
  const worlds::MujocoModel scene = TabletopScene();
  devices::ManualClock clock;
  SimulatedBeacon plate = PlateBeacon(24);
  SimulatedBeacon tool{"tool", "ur5_grip", plate.dwm};  // same frame: one installation
  tool.dwm.seed = 25;
  SimulatedBeaconSource source(scene, {plate, tool}, clock);
  EXPECT_EQ(source.options(1).seed, 25u);
  const calib::RigidTransform uwb_to_table = Inverse(plate.dwm.table_to_uwb);

  std::map<std::string, int> count;
  for (int step = 0; step < 50; ++step) {
    clock.Advance(0.1);
    for (const auto& s : source.Poll()) {
      ++count[s.beacon];
      const Eigen::Vector3d truth =
          SitePosition(scene, s.beacon == "plate" ? "beacon" : "ur5_grip");
      EXPECT_LT((uwb_to_table.Apply(s.position_uwb_m) - truth).head<2>().norm(), 0.3);
    }
  }
  EXPECT_GE(count["plate"], 44);
  EXPECT_GE(count["tool"], 44);
  EXPECT_EQ(count.size(), 2u);
  EXPECT_LE(source.Stats().lines, 100);
  EXPECT_GE(source.Stats().lines, 90);
}

TEST(SimulatedBeaconSourceTest, BadBeaconsAreUserErrors) {
  const worlds::MujocoModel scene = TabletopScene();
  devices::ManualClock clock;
  try {
    SimulatedBeaconSource source(scene, {SimulatedBeacon{"plate", "nowhere", {}}}, clock);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulated beacon 'plate'"));
    EXPECT_THAT(e.what(), HasSubstr("no site 'nowhere'"));
    EXPECT_THAT(e.what(), HasSubstr("beacon"));  // the sites it does have
    EXPECT_THAT(e.what(), HasSubstr("ur5_grip"));
  }
  EXPECT_THROW(SimulatedBeaconSource(scene, {}, clock), UserError);
  EXPECT_THROW(SimulatedBeaconSource(scene, {PlateBeacon(1), PlateBeacon(2)}, clock), UserError);
}

}  // namespace
}  // namespace recon::sim
