#pragma once

#include <string>

#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/scene_assets.h"

namespace recon::worlds::testing {

/// The UR5 on a floor with one graspable 4 cm box at (0.45, 0.1) resting on the floor.
inline MujocoModel MakeArmTestScene() {
  const std::string scene = R"(
<mujoco model="arm test">
  <compiler autolimits="true" angle="radian"/>
  <option timestep="0.002"/>
  <include file="ur5.xml"/>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1"/>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="box" pos="0.45 0.1 0.02">
      <freejoint/>
      <geom type="box" size="0.02 0.02 0.02" mass="0.1" rgba="1 0 0 1"/>
    </body>
  </worldbody>
  <equality>
    <weld name="grasp_box" body1="ur5_gripper" body2="box" active="false"/>
  </equality>
</mujoco>)";
  return MujocoModel::FromFiles({{"scene.xml", scene}, {"ur5.xml", SceneText("ur5.xml")}},
                                "scene.xml", "arm test scene");
}

}  // namespace recon::worlds::testing
