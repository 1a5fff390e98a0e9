#include "app/studio/real_cell_source.h"

#include <filesystem>
#include <utility>

#include "app/cli/session_world.h"
#include "app/studio/cell_view.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/teach/cartesian_teleop.h"

namespace recon::studio {

namespace fs = std::filesystem;

namespace {

/// Whether the session's calibration maps this cell's beacons: one made on a real cell. A
/// session taught in the simulated cell (here for trials) has its simulated beacons' instead.
bool CalibratedHere(const store::SessionManifest& manifest) {
  return manifest.cell == "real" && !manifest.calibration_file.empty();
}

}  // namespace

RealCellSource::RealCellSource(const std::string& profile_path)
    : cell_(std::make_unique<cell::RealCell>(cell::ReadCellProfile(profile_path))) {}

void RealCellSource::DescribeInto(store::SessionManifest& m) const {
  m.cell = "real";
  m.devices.clear();
  for (const cell::CellDeviceStatus& d : cell_->Status()) {
    m.devices.push_back({d.role, d.kind, d.detail});
  }
  m.devices.push_back({"teleop", "keyboard or gamepad", "a person, through the studio"});
}

std::unique_ptr<worlds::World> RealCellSource::MakeNewWorld(const teach::SessionSetup& setup) {
  return MakeWorld(cli::WorldManifest(setup), "");
}

std::unique_ptr<worlds::World> RealCellSource::MakeSessionWorld(const store::Session& session) {
  const store::SessionManifest& m = session.manifest();
  return MakeWorld(
      m, CalibratedHere(m) ? (fs::path(session.dir()) / m.calibration_file).string() : "");
}

std::unique_ptr<worlds::World> RealCellSource::MakeWorld(const store::SessionManifest& manifest,
                                                         const std::string& calibration_path) {
  cell::RealCellWorldOptions options;
  options.placement = manifest.placement;
  options.image_size = manifest.image_size;
  if (!calibration_path.empty() && fs::exists(calibration_path)) {
    options.uwb_to_table = calib::LoadCalibration(calibration_path).transform;
  }
  return cell::MakeRealCellWorld(*cell_, std::move(options));
}

std::optional<devices::JointState> RealCellSource::ArmState() const {
  if (cell_->arm() == nullptr) return std::nullopt;
  try {
    return cell_->arm()->State();
  } catch (const UserError&) {
    return std::nullopt;  // the arm is gone: its device row says so, the screens go on
  }
}

std::optional<Eigen::Vector3d> RealCellSource::GripPoint() const {
  // The point the envelope keeps above the table, in the table frame: what the teacher steers.
  const std::optional<devices::JointState> state = ArmState();
  if (!state) return std::nullopt;
  return cell_->arm()->envelope().ToolPoint(state->position_rad);
}

bool RealCellSource::ShowLive(worlds::World&, const store::Session& session,
                              const std::vector<float>& reading, bool, ViewSize,
                              ui::StudioSnapshot& s) {
  const store::SessionManifest& manifest = session.manifest();
  const bool reading_in_table = CalibratedHere(manifest);
  std::shared_ptr<const devices::CameraFrame> frame;
  try {
    frame = cell_->LatestFrame();
  } catch (const UserError&) {
    // Capture is failing (the camera row says why): the last frame shown stays.
  }
  const bool new_frame = frame && frame->sequence != shown_frame_;
  if (frame) {
    s.camera = frame->image;
    s.camera_frame = static_cast<uint64_t>(frame->sequence) + 1;
    shown_frame_ = frame->sequence;
  }
  for (const char* object : {"plate", "bowl", "toast"}) {
    ui::ObjectView view;
    view.name = object;
    view.located = false;  // a real cell does not know where its objects are: chosen from a list
    s.objects.push_back(view);
  }
  for (const BeaconSpec& b : manifest.beacons) {
    ui::BeaconView view = BeaconViewOf(b, manifest, reading);
    if (reading_in_table && reading.size() == 2) {
      view.pixel = TablePixel({reading[0], reading[1], 0.0});
    }
    s.beacons.push_back(view);
  }
  if (const std::optional<Eigen::Vector3d> grip = GripPoint()) {
    if (auto px = TablePixel(*grip)) s.grip_pixel = *px;
  }
  return new_frame;  // the camera's rate counts frames, not snapshots
}

void RealCellSource::ShowArm(const worlds::World&, ui::StudioSnapshot& s) const {
  const std::optional<devices::JointState> state = ArmState();
  if (!state) return;
  const Eigen::Vector3d grip = cell_->arm()->envelope().ToolPoint(state->position_rad);
  s.grip_m = {static_cast<float>(grip.x()), static_cast<float>(grip.y()),
              static_cast<float>(grip.z())};
  s.gripper_closed = state->gripper_opening < 0.5;
  // A real gripper here reports its opening only: closed, it may or may not hold the toast.
  s.grip.state = s.gripper_closed ? ui::GripState::kUnknown : ui::GripState::kOpen;
  s.grip.wrist_turn_deg = static_cast<float>(
      teach::WristTurn(state->position_rad, teach::TeleopArmOf(cell_->arm()->envelope().limits())) *
      180.0 / M_PI);
  s.grip.wrist_limit_deg = static_cast<float>(teach::kMaxWristTurn_rad * 180.0 / M_PI);
}

void RealCellSource::ShowDevices(ui::StudioSnapshot& s) const {
  std::vector<ui::DeviceView> rows;
  for (const cell::CellDeviceStatus& d : cell_->Status()) {
    rows.push_back({d.role, d.kind, d.detail, d.connected, 0.0, d.last_error});
  }
  if (!cell_->camera_pose()) {
    rows[0].detail += " (no camera pose: " + cell_->camera_pose_error() + ")";
  }
  for (ui::DeviceView& d : s.devices) {
    if (d.role == "teleop") rows.push_back(d);
  }
  s.devices = std::move(rows);
}

Eigen::Vector3d RealCellSource::TeleopVelocity(worlds::World&, const ui::TeleopInput& input,
                                               ViewSize, const worlds::OrbitCamera&,
                                               double speed_m_s) const {
  const std::optional<Eigen::Vector3d> grip = GripPoint();
  if (cell_->camera_pose() && grip) {
    return studio::TeleopVelocity(cell_->camera_pose()->camera, *grip, input, speed_m_s);
  }
  Eigen::Vector3d velocity(input.screen_right, input.screen_up, input.raise);
  if (velocity.head<2>().norm() > 1.0) velocity.head<2>().normalize();
  velocity.z() = std::clamp(velocity.z(), -1.0, 1.0);
  return velocity * speed_m_s;
}

std::optional<std::vector<float>> RealCellSource::IdleBeaconReading(worlds::World& world,
                                                                    const store::Session& session) {
  // Calibrated, the world maps the beacon to the table; before, show that it reports, in its
  // own (UWB) frame.
  if (CalibratedHere(session.manifest())) {
    try {
      return world.BeaconReading();
    } catch (const UserError&) {
      // Not reported yet, or no longer: the last reading stands, and the beacon's rate and the
      // device's row say what is wrong. A recording that needs the reading says so itself.
      return std::nullopt;
    }
  }
  std::vector<float> reading;
  for (const devices::BeaconSample& sample : cell_->beacons().Poll()) {
    reading = {static_cast<float>(sample.position_uwb_m.x()),
               static_cast<float>(sample.position_uwb_m.y())};
  }
  if (reading.empty()) return std::nullopt;
  return reading;
}

std::optional<std::array<float, 2>> RealCellSource::TablePixel(const Eigen::Vector3d& p) const {
  const auto& pose = cell_->camera_pose();
  if (!pose) return std::nullopt;
  const Eigen::Vector2d px = pose->camera.Project(p);
  return std::array<float, 2>{static_cast<float>(px.x()), static_cast<float>(px.y())};
}

}  // namespace recon::studio
