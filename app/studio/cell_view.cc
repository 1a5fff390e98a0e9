#include "app/studio/cell_view.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "devices/cell/scene_camera.h"
#include "engine/teach/cartesian_teleop.h"

namespace recon::studio {

ui::BeaconView BeaconViewOf(const BeaconSpec& beacon, const store::SessionManifest& manifest,
                            const std::vector<float>& reading) {
  ui::BeaconView view;
  view.name = beacon.name;
  auto it = manifest.beacon_assignments.find(beacon.name);
  view.object = it == manifest.beacon_assignments.end() ? "" : it->second;
  view.quantity = beacon.quantity;
  view.unit = beacon.unit;
  view.reading = reading;
  return view;
}

namespace {

// Half the open fingers' span: how long the jaw's axis is drawn either side of the spot.
constexpr double kJawHalfSpan_m = 0.064;

/// Where `camera` shows table point `p`, as the snapshot keeps pixels.
std::array<float, 2> PixelOf(const tags::PinholeCamera& camera, const Eigen::Vector3d& p) {
  const Eigen::Vector2d px = camera.Project(p);
  return {static_cast<float>(px.x()), static_cast<float>(px.y())};
}

/// The jaw's closing axis through the point the drop line lands on, as long as the open fingers
/// span: a grasp holds what lies on this line between them (Ur5Arm::AlignmentWith), so a person
/// lines the toast up with it, or turns the wrist until it crosses the toast.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> JawEnds(const worlds::Tabletop& world) {
  const auto a = world.arm().AlignmentWith("toast");
  if (!a) return std::nullopt;
  Eigen::Vector3d axis = a->closing_axis;
  axis.z() = 0;
  if (axis.norm() < 1e-6) return std::nullopt;
  axis = kJawHalfSpan_m * axis.normalized();
  const Eigen::Vector3d foot = world.SurfaceBelowGrip() + Eigen::Vector3d(0, 0, 0.0006);
  return std::make_pair(foot - axis, foot + axis);
}

}  // namespace

void ShowTabletopView(worlds::Tabletop& world, worlds::SceneRenderer& renderer, int width,
                      int height, const store::SessionManifest& manifest,
                      const std::vector<float>& reading, ui::StudioSnapshot& s) {
  constexpr char kCamera[] = "top";
  s.camera = renderer.Render(world.scene(), kCamera, width, height);
  const tags::PinholeCamera camera = cell::SceneCamera(world.scene(), kCamera, width, height);
  const auto pixel = [&](const Eigen::Vector3d& p) { return PixelOf(camera, p); };
  const auto object = [&](const std::string& name, const Eigen::Vector3d& p) {
    const std::array<float, 2> px = pixel(p);
    s.objects.push_back({name, px[0], px[1]});
  };
  s.grip_pixel = pixel(world.arm().GripPosition());
  if (const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> jaw = JawEnds(world)) {
    const std::array<float, 2> a = pixel(jaw->first), b = pixel(jaw->second);
    s.jaw_camera_pixels = {a[0], a[1], b[0], b[1]};
  }
  object("plate", world.PlatePosition());
  object("bowl", world.BowlPosition());
  object("toast", world.ToastPosition());
  for (const BeaconSpec& b : manifest.beacons) {
    ui::BeaconView view = BeaconViewOf(b, manifest, reading);
    view.pixel = pixel(world.BeaconPosition());
    view.rate_hz = 1.0 / world.StepSeconds();
    s.beacons.push_back(view);
  }
}

worlds::OrbitCamera DefaultTeacherView() {
  worlds::OrbitCamera view;
  view.lookat = Eigen::Vector3d(0.45, 0.0, 0.05);
  view.azimuth_deg = 90.0;
  view.elevation_deg = -35.0;
  view.distance_m = 1.3;
  return view;
}

void ShowTeacherView(worlds::Tabletop& world, worlds::SceneRenderer& renderer,
                     const worlds::OrbitCamera& camera, int width, int height,
                     ui::StudioSnapshot& s) {
  // The drop line from the grip point down to what is under it and a spot where it lands (on
  // the toast when the gripper is over it): with the gripper's shadow, what tells a person how
  // high it is and over what.
  const Eigen::Vector3d grip = world.arm().GripPosition();
  const Eigen::Vector3d foot = world.SurfaceBelowGrip() + Eigen::Vector3d(0, 0, 0.0006);
  constexpr std::array<float, 4> kMarker = {1.0f, 0.85f, 0.1f, 0.9f};
  std::vector<worlds::SceneMarker> markers;
  if (grip.z() > foot.z() + 0.002) {
    markers.push_back({worlds::SceneMarker::Shape::kLine, grip, foot, 0.0015, kMarker});
  }
  markers.push_back({worlds::SceneMarker::Shape::kDisc, foot, foot, 0.012, kMarker});
  // The jaw's closing axis through the spot (JawEnds), also drawn over the view by the screen.
  constexpr std::array<float, 4> kJaw = {0.1f, 0.85f, 0.95f, 0.95f};
  Eigen::Vector3d jaw_a = foot, jaw_b = foot;
  if (const auto jaw = JawEnds(world)) {
    jaw_a = jaw->first;
    jaw_b = jaw->second;
    markers.push_back({worlds::SceneMarker::Shape::kLine, jaw_a, jaw_b, 0.002, kJaw});
  }
  ui::TeacherView& view = s.teacher_view;
  view.available = true;
  view.image = renderer.RenderOrbit(world.scene(), camera, markers, width, height);
  const worlds::OrbitCamera shown = camera.Clamped();
  view.azimuth_deg = static_cast<float>(shown.azimuth_deg);
  view.elevation_deg = static_cast<float>(shown.elevation_deg);
  view.distance_m = static_cast<float>(shown.distance_m);
  const tags::PinholeCamera pinhole = cell::OrbitSceneCamera(world.scene(), shown, width, height);
  view.grip_pixel = PixelOf(pinhole, grip);
  view.spot_pixel = PixelOf(pinhole, foot);
  const std::array<float, 2> a = PixelOf(pinhole, jaw_a), b = PixelOf(pinhole, jaw_b);
  view.jaw_pixels = {a[0], a[1], b[0], b[1]};
}

ui::GripView GripViewOf(const worlds::Tabletop& world) {
  ui::GripView grip;
  grip.object = "toast";
  switch (world.GripOnToast()) {
    case worlds::ToastGrip::kOpen:
      grip.state = ui::GripState::kOpen;
      break;
    case worlds::ToastGrip::kClosing:
      grip.state = ui::GripState::kClosing;
      break;
    case worlds::ToastGrip::kHolding:
      grip.state = ui::GripState::kHolding;
      break;
    case worlds::ToastGrip::kClosedOnNothing:
      grip.state = ui::GripState::kClosedOnNothing;
      break;
  }
  const auto [low, high] = world.GraspHeights();
  grip.grasp_min_m = static_cast<float>(low);
  grip.grasp_max_m = static_cast<float>(high);
  if (const auto a = world.arm().AlignmentWith("toast")) {
    grip.alignment_known = true;
    grip.off_axis_m = static_cast<float>(std::abs(a->along_closing_m));
    grip.off_axis_window_m = static_cast<float>(a->closing_window_m);
    grip.beyond_pads_m = static_cast<float>(std::abs(a->along_faces_m));
    grip.beyond_pads_window_m = static_cast<float>(a->faces_window_m);
    grip.object_distance_m =
        static_cast<float>((world.arm().GripPosition() - world.ToastPosition()).head<2>().norm());
  }
  const safety::SafetyLimits& limits = world.safety_limits();
  grip.wrist_turn_deg = static_cast<float>(
      teach::WristTurn(world.arm().JointPositions(), teach::TeleopArmOf(limits)) * 180.0 / M_PI);
  grip.wrist_limit_deg = static_cast<float>(teach::kMaxWristTurn_rad * 180.0 / M_PI);
  return grip;
}

}  // namespace recon::studio

namespace recon::studio {

namespace {

/// The grip's velocity for a move on the table along `direction` at `deflection` (0-1) of
/// `speed_m_s`, and `raise` (-1-1) up or down: one rule for every view the arrows follow.
Eigen::Vector3d GripVelocity(const Eigen::Vector2d& direction, double deflection, float raise,
                             double speed_m_s) {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  if (deflection > 0 && direction.norm() > 0) {
    velocity.head<2>() = direction.normalized() * deflection * speed_m_s;
  }
  velocity.z() = std::clamp(static_cast<double>(raise), -1.0, 1.0) * speed_m_s;
  return velocity;
}

}  // namespace

Eigen::Vector3d TeleopVelocity(const worlds::OrbitCamera& camera, const ui::TeleopInput& input,
                               double speed_m_s) {
  const Eigen::Vector2d wanted =
      camera.TableRight() * input.screen_right + camera.TableAway() * input.screen_up;
  return GripVelocity(wanted, std::min(1.0, wanted.norm()), input.raise, speed_m_s);
}

Eigen::Vector3d TeleopVelocity(const tags::PinholeCamera& camera, const Eigen::Vector3d& grip,
                               const ui::TeleopInput& input, double speed_m_s) {
  const Eigen::Vector2d at = camera.Project(grip);
  Eigen::Matrix2d to_screen;  // table x, y (per metre) -> pixels
  to_screen.col(0) = (camera.Project(grip + Eigen::Vector3d(0.05, 0, 0)) - at) / 0.05;
  to_screen.col(1) = (camera.Project(grip + Eigen::Vector3d(0, 0.05, 0)) - at) / 0.05;
  const Eigen::Vector2d wanted(input.screen_right, -input.screen_up);  // image rows grow down
  // A camera that sees the table edge-on maps no screen direction to it: no sideways move.
  const Eigen::Vector2d table = std::abs(to_screen.determinant()) > 1e-9
                                    ? Eigen::Vector2d(to_screen.inverse() * wanted)
                                    : Eigen::Vector2d::Zero();
  return GripVelocity(table, std::min(1.0, wanted.norm()), input.raise, speed_m_s);
}

}  // namespace recon::studio
