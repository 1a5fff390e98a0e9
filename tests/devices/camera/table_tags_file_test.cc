#include "devices/camera/table_tags_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "engine/core/error.h"
#include "tests/devices/camera/camera_test_files.h"

namespace recon::camera {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

std::string TableTagsError(const std::string& path) {
  try {
    ReadTableTags(path);
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no UserError)";
}

TEST(TableTagsFileTest, RoundTripsAndPlacesCornersInDetectionOrder) {
  ScratchDir dir;
  const std::vector<TableTag> tags = {{0, {0.1, -0.35, 0.0}, 0.08, 0.0},
                                      {7, {0.7, 0.35, 0.02}, 0.05, M_PI / 2}};
  WriteTableTags(dir / "tags.json", tags);
  const std::vector<TableTag> back = ReadTableTags(dir / "tags.json");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].id, 7);
  EXPECT_TRUE(back[1].center_table_m.isApprox(tags[1].center_table_m));
  EXPECT_DOUBLE_EQ(back[1].size_m, 0.05);
  EXPECT_NEAR(back[1].yaw_rad, M_PI / 2, 1e-12);
  // Yaw 0: the first corner is bottom-left (-x, -y), counter-clockwise seen from above.
  const auto c0 = back[0].Corners();
  EXPECT_TRUE(c0[0].isApprox(Eigen::Vector3d(0.06, -0.39, 0.0)));
  EXPECT_TRUE(c0[1].isApprox(Eigen::Vector3d(0.14, -0.39, 0.0)));
  EXPECT_TRUE(c0[2].isApprox(Eigen::Vector3d(0.14, -0.31, 0.0)));
  // Yaw 90 degrees turns the bottom-left corner to (+x, -y) of the centre, at the tag's height.
  EXPECT_TRUE(back[1].Corners()[0].isApprox(Eigen::Vector3d(0.725, 0.325, 0.02)));
}

TEST(TableTagsFileTest, BadEntriesNameTheFileEntryAndField) {
  ScratchDir dir;
  auto write = [&](const std::string& text) {
    std::ofstream(dir / "t.json") << text;
    return dir / "t.json";
  };
  const std::string path = dir / "t.json";
  EXPECT_THAT(TableTagsError(write("{\"tags\": [{\"id\": 1, \"size_m\": 0.05}]}")),
              HasSubstr(path + ": tags[0]: \"center_m\" must be [x, y, z]"));
  EXPECT_THAT(TableTagsError(write("{\"tags\": [{\"id\": 1, \"center_m\": [0, 0, 0]}]}")),
              HasSubstr("tags[0]: \"size_m\" must be a positive number"));
  EXPECT_THAT(TableTagsError(write("{\"tags\": [{\"center_m\": [0,0,0], \"size_m\": 1}]}")),
              HasSubstr("tags[0]: \"id\" must be a non-negative integer"));
  EXPECT_THAT(TableTagsError(write("{\"tags\": [{\"id\": 1, \"center_m\": [0,0,0], \"size_m\": 1},"
                                   " {\"id\": 1, \"center_m\": [1,0,0], \"size_m\": 1}]}")),
              HasSubstr("tags[1]: tag id 1 is listed twice"));
  EXPECT_THAT(TableTagsError(write("{\"tags\": []}")), HasSubstr("list is empty"));
  EXPECT_THAT(TableTagsError(write("[1, 2")), HasSubstr(path + ": not valid JSON"));
  EXPECT_THAT(TableTagsError(dir / "none.json"), HasSubstr("cannot read the table tags file"));
}

}  // namespace
}  // namespace recon::camera
