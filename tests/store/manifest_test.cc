#include "engine/store/manifest.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "tests/store/store_test_support.h"

namespace recon::store {
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;

std::string ErrorOf(const std::string& text) {
  return testing::ErrorOf([&] { ManifestFromJson(text, "s/session.json"); });
}

json Valid() {
  SessionManifest m = testing::SmallManifest();
  m.episode_flags["demo_2"] = {true, "valid", "dropped the toast"};
  return json::parse(ManifestToJson(m));
}

TEST(ManifestTest, RoundTripsEveryField) {
  SessionManifest m = testing::SmallManifest();
  m.calibration_file = "calibration.json";
  m.beacon_noise_sigma = 0.02;
  m.episode_flags["demo_2"] = {true, "valid", "dropped the toast"};
  m.beacon_assignments["red"] = "bowl";
  m.discarded_takes = 11;
  m.discarded_seconds = 201.5;
  m.countdown_seconds = 45;
  m.teleop = "keyboard";
  EXPECT_EQ(ManifestFromJson(ManifestToJson(m), "x"), m);
}

// The teacher's time that no kept take shows, and the teleop chosen last: absent in a session
// from before them (read as none), refused by name when wrong.
TEST(ManifestTest, TheLedgersUnkeptTimeAndTheTeleopAreOptionalAndChecked) {
  json j = Valid();
  for (const char* field :
       {"discarded_takes", "discarded_seconds", "countdown_seconds", "teleop"}) {
    j["ledger"].erase(field);
  }
  const SessionManifest old = ManifestFromJson(j.dump(), "x");
  EXPECT_EQ(old.discarded_takes, 0);
  EXPECT_EQ(old.discarded_seconds, 0.0);
  EXPECT_EQ(old.countdown_seconds, 0.0);
  EXPECT_EQ(old.teleop, "");
  j = Valid();
  j["ledger"]["discarded_seconds"] = -3;
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'ledger.discarded_seconds' must be a number"));
  j = Valid();
  j["ledger"]["discarded_takes"] = -1;
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("ledger.discarded_takes"));
  j = Valid();
  j["ledger"]["teleop"] = "joystick";
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'ledger.teleop' must be"));
}

TEST(ManifestTest, MissingAndMistypedFieldsAreNamed) {
  json j = Valid();
  j["cell"].erase("world");
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("s/session.json: field 'cell.world' is missing"));
  j = Valid();
  j["beacons"][1]["dim"] = "one";
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'beacons[1].dim' must be an integer"));
  j = Valid();
  j["spec"]["y_shape"] = {3, 0, 4};
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'spec.y_shape' must hold positive integers"));
  j = Valid();
  j["episodes"]["demo_2"]["split"] = "test";
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'episodes.demo_2.split' must be"));
  j = Valid();
  j.erase("seeds");
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'seeds' is missing"));
  j = Valid();
  j["beacons"][0]["name"] = "Red Object";
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'beacons[0].name' must be lower-case"));
}

TEST(ManifestTest, AssignmentsAreOptionalButMustNameABeacon) {
  json j = Valid();
  j.erase("beacon_assignments");
  EXPECT_TRUE(ManifestFromJson(j.dump(), "x").beacon_assignments.empty());
  j["beacon_assignments"] = {{"green", "bowl"}};
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("field 'beacon_assignments.green' names no beacon"));
}

TEST(ManifestTest, BeaconsMustAddUpToTheSpec) {
  json j = Valid();
  j["spec"]["b_dim"] = 5;
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("add up to 3 numbers but spec.b_dim is 5"));
}

TEST(ManifestTest, ANewerVersionIsRefusedWithAnExplanation) {
  json j = Valid();
  j["version"] = kManifestVersion + 1;
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("written by a newer RECON Studio"));
  EXPECT_THAT(ErrorOf(j.dump()),
              HasSubstr("field 'version' is " + std::to_string(kManifestVersion + 1)));
}

TEST(ManifestTest, NotJsonOrNotOursIsSaid) {
  EXPECT_THAT(ErrorOf("{\"format\": "), HasSubstr("s/session.json: not valid JSON"));
  json j = Valid();
  j["format"] = "lerobot";
  EXPECT_THAT(ErrorOf(j.dump()), HasSubstr("not a RECON Studio session manifest"));
  EXPECT_THAT(ErrorOf("[1, 2]"), HasSubstr("must be an object"));
}

}  // namespace
}  // namespace recon::store
