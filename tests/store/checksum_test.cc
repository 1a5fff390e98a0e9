// Every array the store writes carries a checksum (h5.h WriteArray), and a damaged one is a named
// error on read, never data: each dataset of a demonstration and a play file is damaged in turn.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/store/episode_file.h"
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

// Where one chunk of a dataset lies in its file.
struct ChunkPlace {
  std::string dataset;
  haddr_t address = 0;
  hsize_t size = 0;
};

herr_t CollectDatasets(hid_t group, const char* name, const H5L_info_t* /*info*/, void* out) {
  const h5::Handle dataset(H5Dopen2(group, name, H5P_DEFAULT));
  if (dataset.valid()) static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}

// The first chunk of every non-empty dataset in the file; fails the test for a dataset that is
// stored without chunks (and so without a checksum).
std::vector<ChunkPlace> FirstChunks(const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // a group is not a dataset: no printing
  const h5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  EXPECT_TRUE(file.valid()) << path;
  std::vector<std::string> names;
  H5Lvisit(file.id(), H5_INDEX_NAME, H5_ITER_INC, CollectDatasets, &names);
  std::vector<ChunkPlace> chunks;
  for (const std::string& name : names) {
    const h5::Handle dataset(H5Dopen2(file.id(), name.c_str(), H5P_DEFAULT));
    const h5::Handle space(H5Dget_space(dataset.id()));
    if (H5Sget_simple_extent_npoints(space.id()) <= 0) continue;
    const h5::Handle properties(H5Dget_create_plist(dataset.id()));
    const bool is_string = H5Tget_class(h5::Handle(H5Dget_type(dataset.id())).id()) == H5T_STRING;
    if (is_string) continue;  // variable-length strings live on the heap (names, not numbers)
    EXPECT_EQ(H5Pget_layout(properties.id()), H5D_CHUNKED) << path << ": " << name;
    ChunkPlace place{name};
    unsigned filter_mask = 0;
    hsize_t offset[H5S_MAX_RANK] = {};
    if (H5Dget_chunk_info(dataset.id(), space.id(), 0, offset, &filter_mask, &place.address,
                          &place.size) >= 0) {
      chunks.push_back(place);
    }
  }
  return chunks;
}

// A copy of `path` with bytes in the middle of `chunk` changed.
std::string Damaged(const std::string& path, const ChunkPlace& chunk, const std::string& copy) {
  fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
  std::fstream bytes(copy, std::ios::in | std::ios::out | std::ios::binary);
  bytes.seekg(static_cast<std::streamoff>(chunk.address + chunk.size / 2));
  char byte = 0;
  bytes.read(&byte, 1);
  bytes.seekp(static_cast<std::streamoff>(chunk.address + chunk.size / 2));
  byte = static_cast<char>(byte ^ 0x01);  // one flipped bit
  bytes.write(&byte, 1);
  return copy;
}

TEST(ChecksumTest, AFlippedBitInAnyDatasetOfAnEpisodeIsANamedError) {
  TempDir dir("checksum");
  for (const std::string encoding : {"uint8", "float32"}) {
    const SessionManifest layout = SmallManifest(encoding);
    const std::string demo = dir.Path("demo_" + encoding + ".h5");
    const std::string play = dir.Path("play_" + encoding + ".h5");
    DemoRecord demo_record = SyntheticDemo(30, 1);
    demo_record.meta.kind = "demo";
    PlayRecord play_record = SyntheticPlay(12, 2);
    play_record.meta.kind = "play";
    WriteDemoFile(demo, layout, demo_record);
    WritePlayFile(play, layout, play_record);
    for (const auto& [path, is_demo] : {std::pair{demo, true}, std::pair{play, false}}) {
      const std::vector<ChunkPlace> chunks = FirstChunks(path);
      // Robot state, image, beacons (two), and for a demonstration actions and rewards.
      EXPECT_GE(chunks.size(), is_demo ? 6u : 4u) << path;
      for (const ChunkPlace& chunk : chunks) {
        const std::string copy = Damaged(path, chunk, dir.Path("damaged.h5"));
        const std::string error = ErrorOf([&] {
          if (is_demo) {
            ReadDemoFile(copy, layout);
          } else {
            ReadPlayFile(copy, layout);
          }
        });
        EXPECT_THAT(error, HasSubstr(copy)) << chunk.dataset;
        EXPECT_THAT(error, HasSubstr("'" + chunk.dataset + "' is damaged")) << chunk.dataset;
      }
    }
  }
}

TEST(ChecksumTest, AnUndamagedEpisodeReadsBackExactly) {
  // The checksummed, chunked layout holds the same values as the arrays written (the session
  // tests compare every field; this one covers an episode longer than one chunk of images).
  TempDir dir("checksum-long");
  SessionManifest layout = SmallManifest();
  layout.spec.y_shape = {3, 128, 128};  // 48 KiB a frame: 21 frames a 1 MiB chunk
  const std::string path = dir.Path("demo.h5");
  const DemoRecord written = [&] {
    DemoRecord record = SyntheticDemo(50, 3);
    record.meta.kind = "demo";
    for (size_t i = 0; i < record.episode.samples.size(); ++i) {
      record.episode.samples[i].y.assign(3 * 128 * 128, static_cast<float>(i % 256));
    }
    return record;
  }();
  WriteDemoFile(path, layout, written);
  const DemoRecord read = ReadDemoFile(path, layout);
  ASSERT_EQ(read.episode.samples.size(), 50u);
  for (size_t i = 0; i < 50; ++i) {
    EXPECT_EQ(read.episode.samples[i].y, written.episode.samples[i].y) << "frame " << i;
    EXPECT_EQ(read.episode.samples[i].u, written.episode.samples[i].u) << "frame " << i;
  }
  EXPECT_GE(FirstChunks(path).size(), 6u);
}

}  // namespace
}  // namespace recon::store
