#include "engine/worlds/mujoco_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>

#include "engine/core/error.h"

namespace recon::worlds {
namespace {

using ::testing::HasSubstr;

constexpr char kFallingBox[] = R"(
<mujoco model="falling box">
  <compiler autolimits="true"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="box" pos="0 0 0.5">
      <freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.1"/>
    </body>
  </worldbody>
</mujoco>
)";

std::string UserErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MujocoModelTest, LoadedModelSimulatesRealPhysics) {
  MujocoModel m = MujocoModel::FromString(kFallingBox, "falling box");
  ASSERT_EQ(m.model()->nbody, 2);
  const double z0 = m.data()->qpos[2];
  for (int i = 0; i < 100; ++i) mj_step(m.model(), m.data());
  // 100 steps of 2 ms under gravity: the box has fallen about g t^2 / 2 = 0.196 m.
  EXPECT_NEAR(z0 - m.data()->qpos[2], 0.5 * 9.81 * 0.2 * 0.2, 0.01);
  for (int i = 0; i < 1000; ++i) mj_step(m.model(), m.data());
  EXPECT_NEAR(m.data()->qpos[2], 0.05, 0.005);  // resting on the floor
}

TEST(MujocoModelTest, MissingAndBrokenFilesNameTheFile) {
  EXPECT_THAT(UserErrorOf([] { MujocoModel::FromFile("/nonexistent/scene.xml"); }),
              HasSubstr("/nonexistent/scene.xml does not exist"));
  const std::string path = ::testing::TempDir() + "/broken_scene.xml";
  std::ofstream(path) << "<mujoco><worldbody><bogus_element/></worldbody></mujoco>";
  const std::string message = UserErrorOf([&] { MujocoModel::FromFile(path); });
  EXPECT_THAT(message, HasSubstr(path));
  EXPECT_THAT(message, HasSubstr("bogus_element"));
}

TEST(MujocoModelTest, InvalidTextIsAUserErrorWithMujocosReason) {
  const std::string message =
      UserErrorOf([] { MujocoModel::FromString("<mujoco><worldbody>", "half a scene"); });
  EXPECT_THAT(message, HasSubstr("half a scene is not valid MJCF"));
  EXPECT_THAT(UserErrorOf([] {
                MujocoModel::FromString(
                    "<mujoco><worldbody><geom type=\"box\" size=\"-1 1 1\"/></worldbody></mujoco>",
                    "negative box");
              }),
              HasSubstr("negative box"));
}

TEST(MujocoModelTest, MujocoErrorsThrowInsteadOfWaitingForEnter) {
  InstallMujocoErrorHandlers();
  // mju_error runs inside libmujoco; with the default handler this would print "Press Enter to
  // exit" and block the headless test until its time-out.
  EXPECT_THROW(mju_error("deliberate test error"), MujocoError);
  try {
    mju_error("second deliberate error");
  } catch (const MujocoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("second deliberate error"));
  }
  // The process is fine afterwards.
  MujocoModel m = MujocoModel::FromString(kFallingBox, "after the errors");
  mj_step(m.model(), m.data());
  EXPECT_GT(m.data()->time, 0.0);
}

}  // namespace
}  // namespace recon::worlds
