// The cell profile (cell.json): every field read, relative paths resolved against the file's
// folder, the simulated cell's defaults, and each bad field named with the file.

#include "devices/cell/cell_profile.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"

namespace recon::cell {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

void WriteProfileText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

class CellProfileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/recon-cell-profile-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// The message of ReadCellProfile on a cell.json holding `text`.
  std::string ErrorFor(const std::string& text) {
    WriteProfileText(dir_ / "cell.json", text);
    try {
      ReadCellProfile((dir_ / "cell.json").string());
    } catch (const UserError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::string Path() const { return (dir_ / "cell.json").string(); }
  CellProfile ReadText(const std::string& text) {
    WriteProfileText(dir_ / "cell.json", text);
    return ReadCellProfile(Path());
  }

  fs::path dir_;
};

constexpr char kMinimal[] =
    R"({"camera": {"device": "/dev/video0"}, "table_tags": "t.json",
        "beacons": {"ports": ["/dev/ttyACM0"]}})";

TEST_F(CellProfileTest, ReadsEveryFieldAndResolvesRelativePaths) {
  WriteProfileText(dir_ / "cell.json", R"({
    "camera": {"device": "scene/frames", "calibration": "camera.yaml"},
    "table_tags": "table_tags.json",
    "beacons": {"ports": ["/dev/ttyACM0", "by-id/tag"], "mode": "tlv",
                "names": {"0x1A2B": "plate"}},
    "robot": {"host": "192.168.1.10", "rtde_port": 30004, "script_port": 30003},
    "robot_base_in_table": {"xyz_m": [0.1, -0.2, 0.03], "yaw_deg": 90}})");
  const CellProfile p = ReadCellProfile(Path());
  EXPECT_EQ(p.path, Path());
  EXPECT_EQ(p.camera.device, (dir_ / "scene/frames").string());
  EXPECT_EQ(p.camera.calibration, (dir_ / "camera.yaml").string());
  EXPECT_EQ(p.table_tags, (dir_ / "table_tags.json").string());
  EXPECT_EQ(p.beacons.ports,
            (std::vector<std::string>{"/dev/ttyACM0", (dir_ / "by-id/tag").string()}));
  EXPECT_EQ(p.beacons.mode, uwb::Dwm1001Mode::kTlvPolling);
  EXPECT_EQ(p.beacons.names.at("0x1A2B"), "plate");
  ASSERT_TRUE(p.robot.has_value());
  EXPECT_EQ(p.robot->host, "192.168.1.10");
  EXPECT_EQ(p.robot->rtde_port, 30004);
  EXPECT_EQ(p.robot->script_port, 30003);
  EXPECT_TRUE(p.robot_base_in_table.translation().isApprox(Eigen::Vector3d(0.1, -0.2, 0.03)));
  // Yaw 90 degrees: the base's x axis is the table's y axis.
  EXPECT_TRUE((p.robot_base_in_table.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

TEST_F(CellProfileTest, OptionalPartsHaveTheSimulatedCellsDefaults) {
  WriteProfileText(dir_ / "cell.json", kMinimal);
  const CellProfile p = ReadCellProfile(Path());
  EXPECT_EQ(p.camera.device, "/dev/video0") << "a device node is not a relative path";
  EXPECT_FALSE(p.camera.calibration.has_value());
  EXPECT_FALSE(p.robot.has_value());
  EXPECT_TRUE(p.robot_base_in_table.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(p.beacons.mode, uwb::Dwm1001Mode::kLecShell);
  EXPECT_TRUE(p.beacons.names.empty());
  WriteProfileText(dir_ / "cell.json", R"({"camera": {"device": "0"}, "table_tags": "t.json",
      "beacons": {"ports": ["p"]}, "robot": {"host": "ur5"}})");
  const CellProfile q = ReadCellProfile(Path());
  EXPECT_EQ(q.camera.device, "0") << "a V4L2 index stays an index";
  EXPECT_EQ(q.robot->rtde_port, 30004);
  EXPECT_EQ(q.robot->script_port, 30002);
}

TEST_F(CellProfileTest, AMissingFileOrNonJsonIsNamed) {
  EXPECT_THAT([&] { ReadCellProfile((dir_ / "nope.json").string()); },
              ::testing::ThrowsMessage<UserError>(
                  AllOf(HasSubstr((dir_ / "nope.json").string()), HasSubstr("cannot read"))));
  EXPECT_THAT(ErrorFor("camera: /dev/video0\n"),
              AllOf(HasSubstr(Path()), HasSubstr("not valid JSON")));
  EXPECT_THAT(ErrorFor("[1, 2]"), AllOf(HasSubstr(Path()), HasSubstr("expected a JSON object")));
}

TEST_F(CellProfileTest, EachBadFieldIsNamedWithTheFile) {
  const std::string file = Path() + ": ";
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "/dev/video0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["/dev/ttyACM0", 7]}})"),
            file + "beacons.ports[1]: expected a string");
  EXPECT_THAT(ErrorFor(R"({"camera": {"device": "/dev/video0"}, "table_tags": "t.json",
                           "beacons": {"ports": ["/dev/ttyACM0"], "mode": "uart"}})"),
              HasSubstr(file + "beacons.mode: unknown mode \"uart\" (valid: lec, tlv)"));
  EXPECT_EQ(ErrorFor(R"({"table_tags": "t.json", "beacons": {"ports": ["a"]}})"),
            file + "camera: missing");
  EXPECT_EQ(ErrorFor(R"({"camera": {"calibration": "c.yaml"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}})"),
            file + "camera.device: missing");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": 0}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}})"),
            file + "camera.device: expected a string");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "beacons": {"ports": ["a"]}})"),
            file + "table_tags: missing");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json", "beacons": {}})"),
            file + "beacons.ports: missing");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": []}})"),
            file + "beacons.ports: needs at least one serial port");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"], "names": {"plate": "0x1A2B"}}})"),
            file +
                "beacons.names.plate: the key must be a node id in hex, as `si` prints it "
                "(e.g. 0x1A2B)");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"], "names": {"0x1A2B": 3}}})"),
            file + "beacons.names.0x1A2B: expected a string");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}, "robot": {"rtde_port": 30004}})"),
            file + "robot.host: missing");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}, "robot": {"host": "h", "rtde_port": "x"}})"),
            file + "robot.rtde_port: expected a TCP port number (1-65535)");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}, "robot": {"host": "h", "script_port": 70000}})"),
            file + "robot.script_port: expected a TCP port number (1-65535)");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}, "robot_base_in_table": {"xyz_m": [0, 0]}})"),
            file + "robot_base_in_table.xyz_m: expected [x, y, z] in metres");
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}, "robot_base_in_table": {"yaw_deg": "90"}})"),
            file + "robot_base_in_table.yaw_deg: expected a number");
  // A typo must not silently drop the robot.
  EXPECT_THAT(ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                           "beacons": {"ports": ["a"]}, "robto": {"host": "h"}})"),
              HasSubstr(file + "robto: unknown field"));
  EXPECT_THAT(ErrorFor(R"({"camera": {"device": "0", "fps": 30}, "table_tags": "t.json",
                           "beacons": {"ports": ["a"]}})"),
              HasSubstr(file + "camera.fps: unknown field"));
  // A digital twin's camera names its layout; the beacon's tag is what calibration looks for.
  EXPECT_EQ(ErrorFor(R"({"camera": {"device": "twin:"}, "table_tags": "t.json",
                         "beacons": {"ports": ["a"]}})"),
            file + "camera.device: a twin camera names its layout file: twin:layout.json");
  const auto tag_error = [&](const std::string& tag) {
    return ErrorFor(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                        "beacons": {"ports": ["a"]}, "beacon_tag": )" +
                    tag + "}");
  };
  EXPECT_EQ(tag_error(R"({"id": 1.5})"),
            file + "beacon_tag.id: expected a tag36h11 id, a whole number from 0 to 586");
  EXPECT_EQ(tag_error(R"({"id": 587})"),
            file + "beacon_tag.id: expected a tag36h11 id, a whole number from 0 to 586");
  EXPECT_EQ(tag_error(R"({"size_m": 0})"),
            file + "beacon_tag.size_m: expected the black border's side in metres, 0.005 to 0.5");
  EXPECT_EQ(tag_error(R"({"height_m": -0.1})"),
            file +
                "beacon_tag.height_m: expected the tag's height over the table in metres, 0 "
                "to 1");
  EXPECT_THAT(tag_error(R"({"colour": "red"})"), HasSubstr(file + "beacon_tag.colour: unknown"));
}

TEST_F(CellProfileTest, ATwinsLayoutAndTheBeaconTagAreRead) {
  const CellProfile profile = ReadText(R"({"camera": {"device": "twin:twin/layout.json"},
      "table_tags": "t.json", "beacons": {"ports": ["a"]},
      "beacon_tag": {"id": 12, "size_m": 0.04, "height_m": 0.03}})");
  EXPECT_EQ(profile.camera.device, "twin:" + (dir_ / "twin" / "layout.json").string());
  EXPECT_EQ(profile.beacon_tag.id, 12);
  EXPECT_DOUBLE_EQ(profile.beacon_tag.size_m, 0.04);
  EXPECT_DOUBLE_EQ(profile.beacon_tag.height_m, 0.03);
  const CellProfile defaults = ReadText(R"({"camera": {"device": "0"}, "table_tags": "t.json",
      "beacons": {"ports": ["a"]}})");
  EXPECT_EQ(defaults.beacon_tag.id, 10);
  EXPECT_DOUBLE_EQ(defaults.beacon_tag.size_m, 0.0352);
}

TEST_F(CellProfileTest, ABeaconOnTheArmNeedsARobotAndAnOffset) {
  const std::string file = (dir_ / "cell.json").string() + ": ";
  const auto on_arm = [&](const std::string& robot, const std::string& field) {
    return R"({"camera": {"device": "0"}, "table_tags": "t.json", "beacons": {"ports": ["a"]})" +
           robot + R"(, "beacon_on_arm": )" + field + "}";
  };
  const std::string robot = R"(, "robot": {"host": "10.0.0.2"})";
  const CellProfile profile = ReadText(on_arm(robot, R"({"offset_m": [0, 0.01, 0.03]})"));
  ASSERT_TRUE(profile.beacon_on_arm_offset_m.has_value());
  EXPECT_EQ(*profile.beacon_on_arm_offset_m, Eigen::Vector3d(0, 0.01, 0.03));
  EXPECT_FALSE(ReadText(R"({"camera": {"device": "0"}, "table_tags": "t.json",
                            "beacons": {"ports": ["a"]}})")
                   .beacon_on_arm_offset_m.has_value());
  EXPECT_EQ(ErrorFor(on_arm("", R"({"offset_m": [0, 0, 0.03]})")),
            file + "beacon_on_arm: a beacon on the arm needs a robot");
  EXPECT_EQ(ErrorFor(on_arm(robot, R"({"offset_m": [0, 0]})")),
            file + "beacon_on_arm.offset_m: expected [x, y, z] in metres");
  EXPECT_EQ(ErrorFor(on_arm(robot, R"({"offset_m": [0, 0, 2]})")),
            file +
                "beacon_on_arm.offset_m: expected the beacon's offset from the tool point, "
                "within 0.5 m");
  EXPECT_THAT(ErrorFor(on_arm(robot, R"({"offset": [0, 0, 0]})")),
              HasSubstr(file + "beacon_on_arm.offset: unknown field"));
}

}  // namespace
}  // namespace recon::cell
