#include "engine/store/session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/store/h5.h"
#include "tests/store/store_test_support.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::SmallManifest;
using testing::SyntheticDemo;
using testing::SyntheticPlay;
using testing::TempDir;

void ExpectSameEpisode(const Episode& a, const Episode& b) {
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].x, b.samples[i].x) << "sample " << i;
    EXPECT_EQ(a.samples[i].y, b.samples[i].y) << "sample " << i;
    EXPECT_EQ(a.samples[i].b, b.samples[i].b) << "sample " << i;
    EXPECT_EQ(a.samples[i].u, b.samples[i].u) << "sample " << i;
  }
}

TEST(SessionTest, CommittedEpisodesReadBackExactlyInBothEncodings) {
  for (const std::string encoding : {"uint8", "float32"}) {
    TempDir dir("roundtrip-" + encoding);
    const DemoRecord demo = SyntheticDemo(17, 3, encoding == "uint8");
    const PlayRecord play = SyntheticPlay(5, 4);
    {
      Session session = Session::Create(dir.Path("s"), SmallManifest(encoding));
      EXPECT_EQ(session.CommitDemo(demo).name, "demo_0");
      EXPECT_EQ(session.CommitPlay(play).name, "play_0");
    }
    const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
    ASSERT_EQ(session.demos().size(), 1u);
    const DemoRecord back = session.ReadDemo("demo_0");
    ExpectSameEpisode(back.episode, demo.episode);
    EXPECT_EQ(back.rewards, demo.rewards);
    EXPECT_EQ(back.meta.seed, 3u);
    EXPECT_EQ(back.meta.num_samples, 17);
    EXPECT_TRUE(back.meta.succeeded);
    EXPECT_DOUBLE_EQ(back.meta.teaching_seconds, demo.meta.teaching_seconds);
    EXPECT_EQ(session.PlaySamples(), 5);
    const Dataset data = session.LoadDataset({Split::kAll, false, true});
    ASSERT_EQ(data.demos.size(), 1u);
    ASSERT_EQ(data.play.size(), 5u);
    EXPECT_EQ(data.play[2].y, play.samples[2].y);
    EXPECT_EQ(data.play[2].b, play.samples[2].b);
    EXPECT_EQ(data.spec, SmallManifest().spec);
  }
}

TEST(SessionTest, ImagesAreStoredAsRobomimicHwcBytes) {
  TempDir dir("hwc");
  DemoRecord demo = SyntheticDemo(2, 9);
  // Pixel (channel 2, row 1, column 3) of sample 1.
  demo.episode.samples[1].y[2 * 20 + 1 * 5 + 3] = 201.0f;
  Session session = Session::Create(dir.Path("s"), SmallManifest());
  const EpisodeEntry& entry = session.CommitDemo(demo);
  const h5::File file = h5::File::OpenReadOnly(entry.path);
  EXPECT_TRUE(h5::IsUInt8(file, file.id(), "obs/camera_image"));
  EXPECT_EQ(h5::Dimensions(file, file.id(), "obs/camera_image"),
            (std::vector<hsize_t>{2, 4, 5, 3}));
  const std::vector<uint8_t> bytes = h5::ReadBytes(file, file.id(), "obs/camera_image");
  EXPECT_EQ(bytes[((1 * 4 + 1) * 5 + 3) * 3 + 2], 201);
  EXPECT_EQ(h5::Dimensions(file, file.id(), "obs/beacon_red"), (std::vector<hsize_t>{2, 2}));
  EXPECT_EQ(h5::Dimensions(file, file.id(), "obs/beacon_dist"), (std::vector<hsize_t>{2, 1}));
  EXPECT_EQ(h5::ReadIntAttribute(file, file.id(), "num_samples"), 2);
  const std::vector<float> dones = h5::ReadFloats(file, file.id(), "dones");
  EXPECT_EQ(dones, (std::vector<float>{0, 1}));
}

TEST(SessionTest, BadSamplesAreRejectedBeforeAnythingIsCommitted) {
  TempDir dir("reject");
  Session session = Session::Create(dir.Path("s"), SmallManifest());
  DemoRecord fractional = SyntheticDemo(3, 1, /*integral_pixels=*/false);
  EXPECT_THAT(ErrorOf([&] { session.CommitDemo(fractional); }), HasSubstr("not an 8-bit image"));
  DemoRecord nan = SyntheticDemo(3, 1);
  nan.episode.samples[2].u[1] = std::nanf("");
  EXPECT_THAT(ErrorOf([&] { session.CommitDemo(nan); }),
              HasSubstr("sample 2 field 'u' holds a non-finite value"));
  DemoRecord wrong_beacon = SyntheticDemo(3, 1);
  wrong_beacon.episode.samples[0].b.pop_back();
  EXPECT_THAT(ErrorOf([&] { session.CommitDemo(wrong_beacon); }),
              HasSubstr("sample 0 field 'b' has 2 values, the session expects 3"));
  EXPECT_TRUE(session.demos().empty());
  EXPECT_TRUE(fs::is_empty(dir.Path("s/episodes")));  // not even a temporary file
}

TEST(SessionTest, AppendingContinuesNumberingAndDeletedNamesAreNeverReused) {
  TempDir dir("append");
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    session.CommitDemo(SyntheticDemo(3, 1));
    session.CommitDemo(SyntheticDemo(3, 2));
  }
  {
    Session session = Session::Open(dir.Path("s"));
    EXPECT_EQ(session.NextDemoNumber(), 2);
    session.CommitDemo(SyntheticDemo(3, 3));
    session.DeleteEpisode("demo_2");
    EXPECT_TRUE(fs::exists(dir.Path("s/trash/demo_2.h5")));
  }
  Session session = Session::Open(dir.Path("s"));
  ASSERT_EQ(session.demos().size(), 2u);
  EXPECT_EQ(session.NextDemoNumber(), 3);  // demo_2 is in the trash, its name stays taken
  EXPECT_EQ(session.CommitDemo(SyntheticDemo(3, 4)).name, "demo_3");
  EXPECT_THAT(ErrorOf([&] { session.DeleteEpisode("demo_9"); }),
              HasSubstr("has no episode 'demo_9'"));
}

// Undo of a delete: the file comes back from trash/ under its name, with its marks, and the
// session reads it as it did; it cannot come back twice or over a name taken again.
TEST(SessionTest, ADeletedEpisodeComesBackWithItsMarks) {
  TempDir dir("restore");
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    session.CommitDemo(SyntheticDemo(3, 1));
    session.CommitDemo(SyntheticDemo(5, 2));
    session.MarkBad("demo_1", true);
    const EpisodeFlags flags = session.Find("demo_1").flags;
    const std::string trash = session.DeleteEpisode("demo_1");
    EXPECT_TRUE(fs::exists(trash));
    ASSERT_EQ(session.demos().size(), 1u);
    session.RestoreEpisode(trash, "demo_1", flags);
    ASSERT_EQ(session.demos().size(), 2u);
    EXPECT_EQ(session.Find("demo_1").meta.num_samples, 5);
    EXPECT_TRUE(session.Find("demo_1").flags.bad);
    EXPECT_FALSE(fs::exists(trash));
    EXPECT_THAT(ErrorOf([&] { session.RestoreEpisode(trash, "demo_1", flags); }),
                HasSubstr("has an episode of that name again"));
    session.DeleteEpisode("demo_0");
    EXPECT_THAT(ErrorOf([&] { session.RestoreEpisode(trash, "demo_0", {}); }),
                HasSubstr("is no longer in trash/"));
  }
  // What was restored is what a reopened session sees.
  const Session reopened = Session::Open(dir.Path("s"));
  ASSERT_EQ(reopened.demos().size(), 1u);
  EXPECT_EQ(reopened.demos()[0].name, "demo_1");
  EXPECT_TRUE(reopened.demos()[0].flags.bad);
}

TEST(SessionTest, ReRecordingReplacesAnEpisodeAndKeepsTheOldTake) {
  TempDir dir("rerecord");
  Session session = Session::Create(dir.Path("s"), SmallManifest());
  session.CommitDemo(SyntheticDemo(3, 1));
  session.CommitDemo(SyntheticDemo(4, 2));
  session.SetSplit("demo_1", "valid");
  session.MarkBad("demo_1", true);
  const DemoRecord retake = SyntheticDemo(6, 5);
  EXPECT_EQ(session.CommitDemo(retake, std::string("demo_1")).name, "demo_1");
  const EpisodeEntry& entry = session.Find("demo_1");
  EXPECT_EQ(entry.meta.num_samples, 6);
  EXPECT_FALSE(entry.flags.bad);
  EXPECT_EQ(entry.flags.split, "valid");
  ExpectSameEpisode(session.ReadDemo("demo_1").episode, retake.episode);
  EXPECT_EQ(session.ReadDemo("demo_0").meta.num_samples, 3);
  ASSERT_TRUE(fs::exists(dir.Path("s/trash/demo_1.h5")));
  EXPECT_EQ(ReadEpisodeMeta(dir.Path("s/trash/demo_1.h5")).num_samples, 4);
}

TEST(SessionTest, BadEpisodesAndSplitsShapeTheTrainingData) {
  TempDir dir("splits");
  Session session = Session::Create(dir.Path("s"), SmallManifest());
  for (int i = 0; i < 10; ++i) session.CommitDemo(SyntheticDemo(2 + i, 10 + i));
  session.MarkBad("demo_3", true);
  session.AssignSplits(0.3, 5);
  int valid = 0;
  for (const EpisodeEntry& e : session.demos()) valid += e.flags.split == "valid";
  EXPECT_EQ(valid, 3);
  const Dataset train = session.LoadDataset({Split::kTrain, false, false});
  const Dataset valid_data = session.LoadDataset({Split::kValid, false, false});
  const Dataset all = session.LoadDataset({Split::kAll, true, false});
  EXPECT_EQ(all.demos.size(), 10u);
  EXPECT_EQ(train.demos.size() + valid_data.demos.size(), 9u);           // demo_3 is left out
  for (const Episode& e : train.demos) EXPECT_NE(e.samples.size(), 5u);  // demo_3 has 5 samples
  // Reopening keeps the flags (they live in the manifest).
  const std::string split_of_7 = session.Find("demo_7").flags.split;
  session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  EXPECT_TRUE(session.Find("demo_3").flags.bad);
  EXPECT_EQ(session.Find("demo_7").flags.split, split_of_7);
  // The same seed draws the same split.
  TempDir again("splits-again");
  Session other = Session::Create(again.Path("s"), SmallManifest());
  for (int i = 0; i < 10; ++i) other.CommitDemo(SyntheticDemo(2, i));
  other.AssignSplits(0.3, 5);
  for (int i = 0; i < 10; ++i) {
    const std::string name = "demo_" + std::to_string(i);
    EXPECT_EQ(other.Find(name).flags.split, session.Find(name).flags.split) << name;
  }
}

TEST(SessionTest, TheIndexIsARobomimicViewOfTheGoodEpisodes) {
  TempDir dir("index");
  Session session = Session::Create(dir.Path("s"), SmallManifest());
  session.CommitDemo(SyntheticDemo(3, 1));
  session.CommitDemo(SyntheticDemo(4, 2));
  session.CommitDemo(SyntheticDemo(5, 3));
  session.CommitPlay(SyntheticPlay(2, 4));
  session.MarkBad("demo_1", true);
  session.SetSplit("demo_2", "valid");
  const h5::File index = h5::File::OpenReadOnly(dir.Path("s/session.hdf5"));
  const h5::Handle data = h5::OpenGroup(index, index.id(), "data");
  EXPECT_EQ(h5::ListChildren(index, data.id()), (std::vector<std::string>{"demo_0", "demo_2"}));
  EXPECT_EQ(h5::ReadIntAttribute(index, data.id(), "total"), 3 + 5);
  EXPECT_THAT(h5::ReadStringAttribute(index, data.id(), "env_args"),
              HasSubstr("\"env_name\":\"recon/synthetic\""));
  EXPECT_EQ(h5::ReadStrings(index, index.id(), "mask/train"), std::vector<std::string>{"demo_0"});
  EXPECT_EQ(h5::ReadStrings(index, index.id(), "mask/valid"), std::vector<std::string>{"demo_2"});
  // The links resolve: the arrays are reachable through the index file.
  EXPECT_EQ(h5::Dimensions(index, index.id(), "data/demo_2/actions"), (std::vector<hsize_t>{5, 2}));
  EXPECT_EQ(h5::Dimensions(index, index.id(), "play/play_0/obs/beacon_red"),
            (std::vector<hsize_t>{2, 2}));
}

TEST(SessionTest, OpeningRewritesTheIndexOnlyWhenItIsStale) {
  TempDir dir("stale-index");
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    session.CommitDemo(SyntheticDemo(3, 1));
    session.CommitDemo(SyntheticDemo(3, 2));
  }
  const auto written = fs::last_write_time(dir.Path("s/session.hdf5"));
  const auto inode = [&] {
    struct stat info;
    stat(dir.Path("s/session.hdf5").c_str(), &info);
    return info.st_ino;
  };
  const auto inode_before = inode();
  { Session session = Session::Open(dir.Path("s")); }
  EXPECT_EQ(inode(), inode_before);  // up to date: not replaced
  EXPECT_EQ(fs::last_write_time(dir.Path("s/session.hdf5")), written);
  // An episode committed by a writer killed before it rebuilt the index.
  fs::copy_file(dir.Path("s/episodes/demo_1.h5"), dir.Path("s/episodes/demo_2.h5"));
  { Session session = Session::Open(dir.Path("s")); }
  EXPECT_NE(inode(), inode_before);
  const h5::File index = h5::File::OpenReadOnly(dir.Path("s/session.hdf5"));
  const h5::Handle data = h5::OpenGroup(index, index.id(), "data");
  EXPECT_EQ(h5::ListChildren(index, data.id()).size(), 3u);
}

TEST(SessionTest, LeftoverTemporaryFilesOfAKilledWriterAreRemovedOnOpen) {
  TempDir dir("leftover");
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    session.CommitDemo(SyntheticDemo(3, 1));
  }
  {
    std::ofstream half(dir.Path("s/episodes/demo_1.h5.tmp.12345"));
    half << "half an HDF5 file";
  }
  Session read_only = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  EXPECT_EQ(read_only.demos().size(), 1u);
  EXPECT_TRUE(fs::exists(dir.Path("s/episodes/demo_1.h5.tmp.12345")));  // readers never delete
  Session session = Session::Open(dir.Path("s"));
  EXPECT_EQ(session.recovered_temporaries(), 1);
  EXPECT_FALSE(fs::exists(dir.Path("s/episodes/demo_1.h5.tmp.12345")));
  EXPECT_EQ(session.NextDemoNumber(), 1);
}

TEST(SessionTest, TemporariesOfDeadWritersOfDerivedFilesAreRemovedOnOpen) {
  TempDir dir("derived_leftovers");
  { Session session = Session::Create(dir.Path("s"), SmallManifest()); }
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  const std::string dead = std::to_string(child), live = std::to_string(getpid());
  std::vector<std::string> left;
  for (const char* folder : {"checkpoints", "training", "rollouts", "report/figures"}) {
    fs::create_directories(dir.Path(std::string("s/") + folder));
    left.push_back(dir.Path(std::string("s/") + folder + "/x.tmp." + dead));
    std::ofstream(left.back()) << "half a file";
  }
  left.push_back(dir.Path("s/calibration.json.tmp." + dead));
  std::ofstream(left.back()) << "half a file";
  const std::string writing = dir.Path("s/checkpoints/recon.ckpt.tmp." + live);
  std::ofstream(writing) << "a live writer's file";
  {
    Session read_only = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
    for (const std::string& path : left) EXPECT_TRUE(fs::exists(path)) << path;
  }
  Session session = Session::Open(dir.Path("s"));
  EXPECT_EQ(session.recovered_temporaries(), static_cast<int>(left.size()));
  for (const std::string& path : left) EXPECT_FALSE(fs::exists(path)) << path;
  EXPECT_TRUE(fs::exists(writing));
}

TEST(SessionTest, OnlyOneWriterAtATime) {
  TempDir dir("lock");
  Session writer = Session::Create(dir.Path("s"), SmallManifest());
  EXPECT_THAT(ErrorOf([&] { Session::Open(dir.Path("s")); }),
              HasSubstr("is being written by another process"));
  const Session reader = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  EXPECT_THAT(ErrorOf([&] { const_cast<Session&>(reader).MarkBad("demo_0", true); }),
              HasSubstr("opened read-only"));
}

TEST(SessionTest, DamagedEpisodesAreNamedAndTheRestStayUsable) {
  TempDir dir("damaged");
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    session.CommitDemo(SyntheticDemo(30, 1));
    session.CommitDemo(SyntheticDemo(30, 2));
    session.CommitDemo(SyntheticDemo(30, 3));
  }
  // Truncate demo_1 (a disk that filled up, a copy interrupted by hand) and garble demo_2.
  const std::string truncated = dir.Path("s/episodes/demo_1.h5");
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  {
    std::fstream garbled(dir.Path("s/episodes/demo_2.h5"), std::ios::in | std::ios::out);
    garbled.seekp(0);
    garbled << "this is not HDF5";
  }
  Session session = Session::Open(dir.Path("s"));
  ASSERT_EQ(session.demos().size(), 3u);
  EXPECT_TRUE(session.Find("demo_0").problem.empty());
  EXPECT_THAT(session.Find("demo_1").problem, HasSubstr("demo_1.h5"));
  EXPECT_THAT(session.Find("demo_2").problem, HasSubstr("demo_2.h5"));
  EXPECT_THAT(ErrorOf([&] { session.LoadDataset(); }), HasSubstr("episodes/demo_1.h5"));
  EXPECT_THAT(ErrorOf([&] { session.LoadDataset(); }), HasSubstr("delete-episode"));
  // The good episode is untouched and the damaged ones can be put aside.
  session.DeleteEpisode("demo_1");
  session.DeleteEpisode("demo_2");
  const Dataset data = session.LoadDataset();
  ASSERT_EQ(data.demos.size(), 1u);
  ExpectSameEpisode(data.demos[0], SyntheticDemo(30, 1).episode);
}

TEST(SessionTest, AnEpisodeWithOtherBeaconDimensionsIsNamedWithItsDataset) {
  TempDir dir("beacon-dims");
  SessionManifest other = SmallManifest();
  other.beacons[0].dim = 3;  // "red" reads 3 numbers in this session
  other.spec.b_dim = 4;
  DemoRecord demo = SyntheticDemo(4, 1);
  for (Sample& s : demo.episode.samples) s.b.push_back(0.5f);
  {
    Session foreign = Session::Create(dir.Path("other"), other);
    foreign.CommitDemo(demo);
  }
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    session.CommitDemo(SyntheticDemo(4, 2));
  }
  fs::copy_file(dir.Path("other/episodes/demo_0.h5"), dir.Path("s/episodes/demo_1.h5"));
  const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  EXPECT_THAT(session.Find("demo_1").problem,
              HasSubstr("dataset 'obs/beacon_red' has shape (4, 3), the session expects (4, 2)"));
  EXPECT_THAT(session.Find("demo_1").problem, HasSubstr("episodes/demo_1.h5"));
  EXPECT_TRUE(session.Find("demo_0").problem.empty());
}

TEST(SessionTest, OpeningSomethingThatIsNotASessionSaysSo) {
  TempDir dir("not-a-session");
  EXPECT_THAT(ErrorOf([&] { Session::Open(dir.Path()); }), HasSubstr("is not a teaching session"));
  Session::Create(dir.Path("s"), SmallManifest());
  EXPECT_THAT(ErrorOf([&] { Session::Create(dir.Path("s"), SmallManifest()); }),
              HasSubstr("already holds a teaching session"));
}

}  // namespace
}  // namespace recon::store
