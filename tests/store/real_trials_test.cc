// A method's trials on a real arm (trials/<method>.json) and each trial's frames
// (trials/<method>/trial_<n>.h5): written atomically, read back field for field, and every kind
// of damage named.

#include "engine/store/real_trials.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/store/store_test_support.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::TempDir;
using testing::WriteText;

RealTrialLog TwoTrials() {
  RealTrialLog log;
  log.method = "recon";
  log.label = "RECON (Play)";
  log.model_id = "fnv1a:00c0ffee00c0ffee";
  log.cell = "real";
  RealTrial first;
  first.number = 1;
  first.scene_seed = 123456789012345ull;
  first.layout = {{"plate", {0.55, 0.35}}, {"bowl", {0.4, -0.2}}, {"toast", {0.35, 0.0}}};
  first.succeeded = true;
  first.steps = 143;
  first.seconds = 14.3;
  first.frames = Session::TrialFramesRelativePath("recon", 1);
  first.judged_at = "2026-12-05T09:00:00Z";
  RealTrial second = first;
  second.number = 2;
  second.succeeded = false;
  second.reason = "took it to the bowl";
  second.stopped = true;
  second.frames.reset();
  log.trials = {first, second};
  return log;
}

TEST(RealTrialsTest, ALogIsReadBackFieldForFieldWithItsSuccessRate) {
  const TempDir dir("trials");
  const RealTrialLog log = TwoTrials();
  const std::string path = dir.Path("trials/recon.json");
  WriteRealTrialLog(path, log);
  const json written = json::parse(std::ifstream(path));
  EXPECT_EQ(written["successes"], 1);
  EXPECT_DOUBLE_EQ(written["success_rate"].get<double>(), 0.5);
  EXPECT_EQ(RealTrialLogFromJson(written, path, "recon"), log);
  EXPECT_EQ(log.successes(), 1);
  EXPECT_DOUBLE_EQ(RealTrialLog{}.success_rate(), 0.0);
}

TEST(RealTrialsTest, DamageIsNamedWithTheFileAndTheField) {
  const std::string source = "trials/recon.json";
  json value = RealTrialLogToJson(TwoTrials());
  value["trials"][1]["number"] = 3;
  EXPECT_THAT(ErrorOf([&] { RealTrialLogFromJson(value, source, "recon"); }),
              HasSubstr("trials/recon.json: trials[1].number: trial 3 where trial 2 was expected"));
  value = RealTrialLogToJson(TwoTrials());
  value["trials"][0]["frames"] = "../../etc/passwd";
  EXPECT_THAT(ErrorOf([&] { RealTrialLogFromJson(value, source, "recon"); }),
              HasSubstr("is not a path inside the session"));
  value = RealTrialLogToJson(TwoTrials());
  value["trials"][0]["layout"]["plate"] = "left";
  EXPECT_THAT(ErrorOf([&] { RealTrialLogFromJson(value, source, "recon"); }),
              HasSubstr("plate: expected [x, y] in metres"));
  value = RealTrialLogToJson(TwoTrials());
  value["trials"][0]["succeeded"] = "yes";
  EXPECT_THAT(ErrorOf([&] { RealTrialLogFromJson(value, source, "recon"); }),
              HasSubstr("succeeded"));
  value.erase("trials");
  EXPECT_THAT(ErrorOf([&] { RealTrialLogFromJson(value, source, "recon"); }), HasSubstr("trials"));
}

TEST(RealTrialsTest, FramesAreReadBackAndDamagedOnesAreRefused) {
  const TempDir dir("trial-frames");
  TrialFrames frames;
  frames.image_size = 2;
  for (int t = 0; t < 3; ++t) {
    frames.x.push_back({0.1f * t, -0.2f});
    std::vector<float> y(12);
    for (int i = 0; i < 12; ++i) y[i] = static_cast<float>(20 * t + i);
    frames.y.push_back(y);
    frames.u.push_back({0.5f, static_cast<float>(t)});
  }
  const std::string path = dir.Path("trials/recon/trial_1.h5");
  WriteTrialFrames(path, frames);
  const TrialFrames back = ReadTrialFrames(path);
  EXPECT_EQ(back.image_size, 2);
  EXPECT_EQ(back.x, frames.x);
  EXPECT_EQ(back.y, frames.y);
  EXPECT_EQ(back.u, frames.u);

  TrialFrames ragged = frames;
  ragged.u[1].push_back(1.0f);
  EXPECT_THAT(ErrorOf([&] { WriteTrialFrames(dir.Path("ragged.h5"), ragged); }),
              HasSubstr("u row 1 has 3 values, the first 2"));
  TrialFrames wrong_image = frames;
  wrong_image.image_size = 3;
  EXPECT_THAT(ErrorOf([&] { WriteTrialFrames(dir.Path("image.h5"), wrong_image); }),
              HasSubstr("not 3 x 3 x 3"));
  EXPECT_FALSE(fs::exists(dir.Path("image.h5")));
  WriteText(dir.Path("text.h5"), "not hdf5");
  EXPECT_THAT(ErrorOf([&] { ReadTrialFrames(dir.Path("text.h5")); }), HasSubstr("text.h5"));
  EXPECT_THAT(ErrorOf([&] { ReadTrialFrames(dir.Path("missing.h5")); }), HasSubstr("missing.h5"));
}

}  // namespace
}  // namespace recon::store
