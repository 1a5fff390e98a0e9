// The distractor probe on the simulated tabletop (real MuJoCo, real EGL rendering): an object
// moved by the probe is drawn where it was put with everything else held, and a policy that
// reads only the bowl's colour is found to look at the bowl and not at the plate.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/probe/distractor_probe.h"
#include "engine/worlds/tabletop.h"

namespace recon::worlds {
namespace {

using ::testing::HasSubstr;

std::unique_ptr<Tabletop> ProbeTabletop() {
  TabletopOptions options;
  options.placement = "none";  // as rollouts run
  return std::make_unique<Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

/// The centroid (pixels) of the bowl's red in a channels-first 0-255 image; (-1, -1) if none.
std::vector<float> RedCentroid(const std::vector<float>& y, int size) {
  const size_t plane = static_cast<size_t>(size) * size;
  double sx = 0, sy = 0, n = 0;
  for (size_t p = 0; p < plane; ++p) {
    if (y[p] > 150 && y[plane + p] < 90 && y[2 * plane + p] < 90) {
      sx += static_cast<double>(p % size);
      sy += static_cast<double>(p / size);
      ++n;
    }
  }
  if (n == 0) return {-1, -1};
  return {static_cast<float>(sx / n), static_cast<float>(sy / n)};
}

TEST(TabletopProbeTest, AMovedObjectIsDrawnWhereItWasPutWithEverythingElseHeld) {
  std::unique_ptr<Tabletop> world = ProbeTabletop();
  world->Reset(7);
  const auto before = world->ObjectLayout();
  const std::vector<float> x_before = world->Observe().x;
  world->PlaceObject("bowl", {0.7, -0.2});
  const auto after = world->ObjectLayout();
  EXPECT_NEAR(after.at("bowl")[0], 0.7, 1e-9);
  EXPECT_NEAR(after.at("bowl")[1], -0.2, 1e-9);
  EXPECT_EQ(after.at("plate"), before.at("plate"));
  EXPECT_EQ(after.at("toast"), before.at("toast"));
  EXPECT_EQ(world->Observe().x, x_before);  // the arm held
  world->PlaceObject("toast", {0.4, 0.1});
  EXPECT_NEAR(world->ToastPosition().x(), 0.4, 1e-9);
  // The plate carries its beacon along.
  const Eigen::Vector3d beacon_from_plate = world->BeaconPosition() - world->PlatePosition();
  world->PlaceObject("plate", {0.6, 0.3});
  EXPECT_LT((world->BeaconPosition() - world->PlatePosition() - beacon_from_plate).norm(), 1e-9);
  EXPECT_NEAR(world->PlatePosition().y(), 0.3, 1e-9);
  try {
    world->PlaceObject("cup", {0.5, 0.0});
    ADD_FAILURE() << "an unknown object was placed";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("valid: bowl, plate, toast"));
  }
}

TEST(TabletopProbeTest, APolicyThatReadsTheBowlIsFoundToLookAtTheBowlNotThePlate) {
  std::unique_ptr<Tabletop> world = ProbeTabletop();
  const int size = static_cast<int>(world->Spec().y_shape[1]);
  probe::ProbeSubject reads_bowl;
  reads_bowl.method = "bowl-reader";
  reads_bowl.label = "Reads the bowl";
  reads_bowl.act = [size](const probe::ProbeSubject::Rows&, const probe::ProbeSubject::Rows& ys) {
    probe::ProbeSubject::Rows out;
    for (const auto& y : ys) out.push_back(RedCentroid(y, size));
    return out;
  };
  reads_bowl.features = reads_bowl.act;
  probe::ProbeGrid grid;
  grid.nx = grid.ny = 5;
  const probe::ProbeResult result =
      probe::ProbeObjects(*world, 7, {"bowl", "plate"}, grid, {reads_bowl});
  ASSERT_EQ(result.probes.size(), 1u);
  const probe::ObjectProbe& bowl = result.probes[0][0];
  const probe::ObjectProbe& plate = result.probes[0][1];
  EXPECT_EQ(bowl.object, "bowl");
  // 64 pixels over about 1 m of table: several pixels per 10 cm for the bowl, none for the plate.
  EXPECT_GT(bowl.action_change_per_10cm, 2.0);
  EXPECT_LT(plate.action_change_per_10cm, 0.1 * bowl.action_change_per_10cm);
}

}  // namespace
}  // namespace recon::worlds
