#include "devices/cell/real_cell_world.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "engine/core/error.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::cell {

namespace {

constexpr int kJoints = worlds::Ur5Arm::kJoints;

/// For each output index, the input indices it covers with their weights (summing to 1): the
/// overlap of [o * n / size, (o + 1) * n / size) with each input cell.
std::vector<std::vector<std::pair<int, double>>> AreaWeights(int n, int size) {
  std::vector<std::vector<std::pair<int, double>>> weights(size);
  const double scale = static_cast<double>(n) / size;
  for (int o = 0; o < size; ++o) {
    const double begin = o * scale, end = (o + 1) * scale;
    for (int i = static_cast<int>(std::floor(begin)); i < n && i < end; ++i) {
      const double overlap = std::min(end, i + 1.0) - std::max(begin, static_cast<double>(i));
      if (overlap > 1e-12) weights[o].push_back({i, overlap / scale});
    }
  }
  return weights;
}

}  // namespace

std::vector<float> AreaAveragedChannelsFirst(const RgbImage& image, int size) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    throw std::invalid_argument("AreaAveragedChannelsFirst: an empty or inconsistent image");
  }
  const auto rows = AreaWeights(image.height, size);
  const auto cols = AreaWeights(image.width, size);
  // Columns first (per input row), then rows: separable, so each input pixel is read once.
  std::vector<double> narrow(static_cast<size_t>(image.height) * size * 3, 0.0);
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < size; ++c) {
      double* out = &narrow[(static_cast<size_t>(r) * size + c) * 3];
      for (const auto& [col, w] : cols[c]) {
        const uint8_t* px = image.Pixel(r, col);
        for (int ch = 0; ch < 3; ++ch) out[ch] += w * px[ch];
      }
    }
  }
  const size_t plane = static_cast<size_t>(size) * size;
  std::vector<float> y(3 * plane);
  for (int r = 0; r < size; ++r) {
    for (int c = 0; c < size; ++c) {
      double sum[3] = {0, 0, 0};
      for (const auto& [row, w] : rows[r]) {
        const double* in = &narrow[(static_cast<size_t>(row) * size + c) * 3];
        for (int ch = 0; ch < 3; ++ch) sum[ch] += w * in[ch];
      }
      for (int ch = 0; ch < 3; ++ch) {
        y[ch * plane + static_cast<size_t>(r) * size + c] = static_cast<float>(std::round(sum[ch]));
      }
    }
  }
  return y;
}

RealCellWorld::RealCellWorld(const LatestFrameSource& camera, devices::BeaconSource& beacons,
                             devices::Arm& arm, const devices::Clock& clock,
                             RealCellWorldOptions options)
    : camera_(camera), beacons_(beacons), arm_(arm), clock_(clock), options_(std::move(options)) {
  if (options_.placement != "none" && options_.placement != "plate") {
    throw UserError("unknown tabletop beacon placement '" + options_.placement +
                    "' (valid: none, plate)");
  }
  if (options_.image_size < 16) {
    throw UserError("tabletop camera images must be at least 16 x 16 pixels");
  }
  if (!(options_.beacon_max_age_s > 0)) {
    throw UserError("the beacon's maximum reading age must be a positive number of seconds");
  }
}

std::string RealCellWorld::CameraName() const {
  return options_.camera_name.empty() ? camera_.Describe() : options_.camera_name;
}
std::string RealCellWorld::BeaconsName() const {
  return options_.beacons_name.empty() ? beacons_.Describe() : options_.beacons_name;
}
std::string RealCellWorld::ArmName() const {
  return options_.arm_name.empty() ? arm_.Describe() : options_.arm_name;
}

DataSpec RealCellWorld::Spec() const {
  DataSpec spec;
  spec.x_dim = kJoints + 1;
  spec.y_shape = {3, options_.image_size, options_.image_size};
  spec.b_dim = options_.placement == "none" ? 0 : 2;
  spec.u_dim = kJoints + 1;
  return spec;
}

void RealCellWorld::Reset(uint64_t seed) {
  (void)seed;
  try {
    arm_.Stop();
  } catch (const UserError& e) {
    throw UserError("arm " + ArmName() + ": " + e.what());
  }
  last_step_s_.reset();
}

worlds::Observation RealCellWorld::Observe() const {
  devices::JointState state;
  try {
    state = arm_.State();
  } catch (const UserError& e) {
    throw UserError("arm " + ArmName() + ": " + e.what());
  }
  // Latest() names the camera in its own errors.
  const std::shared_ptr<const devices::CameraFrame> frame = camera_.Latest();
  if (frame == nullptr) {
    throw UserError("camera " + CameraName() + " has not delivered a frame yet");
  }
  worlds::Observation o;
  // As Tabletop: angles relative to the home pose, so recordings from either cell train alike.
  for (int i = 0; i < kJoints; ++i) {
    o.x.push_back(static_cast<float>(state.position_rad[i] - worlds::Ur5Arm::kHome[i]));
  }
  o.x.push_back(static_cast<float>(state.gripper_opening));
  o.y = AreaAveragedChannelsFirst(frame->image, options_.image_size);
  return o;
}

void RealCellWorld::Step(const std::vector<float>& u) {
  if (static_cast<int>(u.size()) != kJoints + 1) {
    throw std::invalid_argument("tabletop action must have 7 entries");
  }
  std::array<double, 6> qd;
  for (int i = 0; i < kJoints; ++i) qd[i] = u[i];  // NaN included: the envelope makes it a stop
  const bool close = u[kJoints] > 0.5f;
  try {
    arm_.CommandJointVelocities(qd);
    // Only changes go out, judged by the arm's own state (a teleop screen may have moved the
    // gripper too): the gripper holds its state, and the script port is not flooded.
    if ((arm_.State().gripper_opening < 0.5) != close) arm_.CommandGripper(close);
  } catch (const UserError& e) {
    throw UserError("arm " + ArmName() + ": " + e.what());
  }
  const double now_s = clock_.NowSeconds();
  if (last_step_s_ && now_s < *last_step_s_ + kControlPeriod_s) {
    const double target_s = *last_step_s_ + kControlPeriod_s;
    std::this_thread::sleep_for(std::chrono::duration<double>(target_s - now_s));
    last_step_s_ = target_s;  // on schedule: small sleep overshoots do not accumulate
  } else {
    last_step_s_ = now_s;  // late (a slow policy): start a new schedule rather than rush
  }
}

std::vector<float> RealCellWorld::ExpertAction() const {
  throw UserError("a real cell has no scripted expert: teach with the keyboard or a gamepad");
}

std::vector<float> RealCellWorld::BeaconReading() {
  if (options_.placement == "none") return {};
  if (!options_.uwb_to_table) {
    throw UserError(
        "calibrate the cell first: the plate beacon's UWB position cannot be put on the table "
        "without the UWB -> table calibration");
  }
  std::vector<devices::BeaconSample> samples;
  try {
    samples = beacons_.Poll();
  } catch (const UserError& e) {
    throw UserError("beacons " + BeaconsName() + ": " + e.what());
  }
  for (const devices::BeaconSample& s : samples) {
    if (s.beacon != options_.plate_beacon || !s.position_uwb_m.allFinite()) continue;
    plate_uwb_m_ = s.position_uwb_m;
    plate_seen_s_ = clock_.NowSeconds();
  }
  if (!plate_uwb_m_) {
    throw UserError("beacon '" + options_.plate_beacon + "' has not reported a position yet (" +
                    BeaconsName() + ")");
  }
  const double age_s = clock_.NowSeconds() - plate_seen_s_;
  if (age_s > options_.beacon_max_age_s) {
    throw UserError("beacon '" + options_.plate_beacon + "' has been silent for " +
                    std::to_string(age_s) + " s (unplugged? " + BeaconsName() + ")");
  }
  const Eigen::Vector3d table_m = options_.uwb_to_table->Apply(*plate_uwb_m_);
  return {static_cast<float>(table_m.x()), static_cast<float>(table_m.y())};
}

PlaySample RealCellWorld::SamplePlay() {
  const worlds::Observation o = Observe();
  return PlaySample{o.x, o.y, BeaconReading()};
}

worlds::WorldTraits RealCellWorld::Traits() const {
  worlds::WorldTraits traits;
  traits.metric_name = "not measured in a real cell (the teacher judges the outcome)";
  traits.step_seconds = kControlPeriod_s;
  return traits;
}

}  // namespace recon::cell
