#include "engine/worlds/tabletop.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/scene_assets.h"
#include "engine/worlds/tabletop_waypoints.h"
#include "engine/worlds/tag_textures.h"

namespace recon::worlds {

// The expert's heights, which the reachability check and DemonstrationDone share with it.
using namespace tabletop_waypoints;  // NOLINT(build/namespaces)

namespace {

constexpr char kCamera[] = "top";
// Scenario layout, table frame (metres). The plate is at the left or the right edge: in the
// paper's layout at one marked place per side (a person puts it there to within about 1 cm), in
// the wide layout anywhere in a band along the edge.
constexpr double kPaperPlateX = 0.56, kPaperPlateAbsY = 0.33, kPaperPlateJitter_m = 0.01;
constexpr double kPlateMinX = 0.45, kPlateMaxX = 0.68;
constexpr double kPlateMinAbsY = 0.30, kPlateMaxAbsY = 0.36;
// The paper's robot experiment records two takes of every plate-and-bowl configuration, the
// plate on one side of the table or the other: four demonstrations.
constexpr int kPaperDemosPerConfiguration = 2;
constexpr int kPlateSides = 2;
// The toast waits at a fixed pick-up place (the paper does not say; a toaster or a plate of toast
// by the robot): at 64 x 64 pixels a 2 cm shift is one pixel, too little to steer a grasp by.
constexpr double kToastX = 0.33, kToastJitter = 0.0;
// A slice of toast: 10 x 10 x 1.6 cm (assets/mjcf/tabletop.xml).
constexpr double kToastRestZ = 0.008;
// How far below its resting height the toast's middle must be to have left the table.
constexpr double kToastOffTableDrop_m = 0.05;
constexpr double kBowlClearPlate = 0.22, kBowlClearToast = 0.16, kBowlClearBeacon = 0.12;
Eigen::Vector3d Vec(const mjtNum* p) { return {p[0], p[1], p[2]}; }

}  // namespace

const std::vector<std::string>& Tabletop::Layouts() {
  static const std::vector<std::string> layouts = {"paper", "wide"};
  return layouts;
}

const std::vector<std::string>& Tabletop::Placements() {
  static const std::vector<std::string> placements = {"none", "plate"};
  return placements;
}

Tabletop::Tabletop(const TabletopOptions& options, std::unique_ptr<SceneRenderer> renderer)
    : options_(options), renderer_(std::move(renderer)), scene_(LoadScene("tabletop")) {
  const auto& placements = Placements();
  if (std::find(placements.begin(), placements.end(), options_.placement) == placements.end()) {
    throw UserError("unknown tabletop beacon placement '" + options_.placement +
                    "' (valid: " + JoinNames(placements) + ")");
  }
  const auto& layouts = Layouts();
  if (std::find(layouts.begin(), layouts.end(), options_.layout) == layouts.end()) {
    throw UserError("unknown tabletop layout '" + options_.layout +
                    "' (valid: " + JoinNames(layouts) + ")");
  }
  if (!std::isfinite(options_.noise_sigma_m) || options_.noise_sigma_m < 0 ||
      options_.noise_sigma_m > kMaxBeaconNoise_m) {
    throw UserError("beacon noise must be between 0 and " + FormatNumber(kMaxBeaconNoise_m) +
                    " metres (got " + FormatNumber(options_.noise_sigma_m) + ")");
  }
  if (options_.image_width < 16 || options_.image_height < 16) {
    throw UserError("tabletop camera images must be at least 16 x 16 pixels");
  }
  if (options_.observation != "image" && options_.observation != "state") {
    throw UserError("unknown tabletop observation '" + options_.observation +
                    "' (valid: image, state)");
  }
  if (renderer_ == nullptr && options_.observation == "image") {
    throw UserError("the tabletop world needs a scene renderer");
  }
  PaintTagTextures(scene_);
  arm_ = std::make_unique<Ur5Arm>(scene_);
  guarded_ = std::make_unique<GuardedUr5>(*arm_, kControlPeriod_s);
  const mjModel* m = scene_.model();
  plate_body_ = mj_name2id(m, mjOBJ_BODY, "plate");
  bowl_body_ = mj_name2id(m, mjOBJ_BODY, "bowl");
  toast_body_ = mj_name2id(m, mjOBJ_BODY, "toast");
  beacon_site_ = mj_name2id(m, mjOBJ_SITE, "beacon");
  toast_qpos_ = m->jnt_qposadr[m->body_jntadr[toast_body_]];
  Reset(0);
}

DataSpec Tabletop::Spec() const {
  DataSpec spec;
  spec.x_dim = Ur5Arm::kJoints + 1;
  spec.y_shape = options_.observation == "state"
                     ? std::vector<int64_t>{6}
                     : std::vector<int64_t>{3, options_.image_height, options_.image_width};
  spec.b_dim = options_.placement == "none" ? 0 : 2;
  spec.u_dim = Ur5Arm::kJoints + 1;
  return spec;
}

void Tabletop::PlaceMocap(int body, const Eigen::Vector3d& position) {
  const int mocap = scene_.model()->body_mocapid[body];
  for (int k = 0; k < 3; ++k) scene_.data()->mocap_pos[3 * mocap + k] = position[k];
}

Eigen::Vector3d Tabletop::DrawBowlPosition(Rng& rng) const {
  const Eigen::Vector3d plate = PlatePosition(), toast = ToastPosition();
  const Eigen::Vector3d beacon = BeaconPosition();
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const Eigen::Vector3d bowl(rng.Uniform(kBowlMinX, kBowlMaxX),
                               rng.Uniform(-kBowlMaxAbsY, kBowlMaxAbsY), 0.0);
    if (PlanarDistance(bowl, plate) >= kBowlClearPlate &&
        PlanarDistance(bowl, toast) >= kBowlClearToast &&
        PlanarDistance(bowl, beacon) >= kBowlClearBeacon) {
      return bowl;
    }
  }
  throw std::logic_error("tabletop: no free place for the bowl (layout constants are wrong)");
}

Eigen::Vector3d Tabletop::DrawPlatePosition(int side, Rng& rng) const {
  if (options_.layout == "paper") {
    return {kPaperPlateX + rng.Uniform(-kPaperPlateJitter_m, kPaperPlateJitter_m),
            side * kPaperPlateAbsY + rng.Uniform(-kPaperPlateJitter_m, kPaperPlateJitter_m), 0.0};
  }
  return {rng.Uniform(kPlateMinX, kPlateMaxX), side * rng.Uniform(kPlateMinAbsY, kPlateMaxAbsY),
          0.0};
}

void Tabletop::Reset(uint64_t seed) {
  rng_.Seed(seed);
  mj_resetData(scene_.model(), scene_.data());
  plate_side_ = rng_.Uniform() < 0.5 ? 1 : -1;
  PlaceMocap(plate_body_, DrawPlatePosition(plate_side_, rng_));
  PlaceToastAndArm();  // runs mj_forward: the bowl below keeps clear of the current positions
  PlaceMocap(bowl_body_, DrawBowlPosition(rng_));
  FinishReset();
}

int Tabletop::DemosPerConfiguration() const {
  return options_.layout == "paper" ? kPaperDemosPerConfiguration : 1;
}

int Tabletop::SuggestedDemos() const { return kPlateSides * kPaperDemosPerConfiguration; }

void Tabletop::ResetTake(uint64_t seed, uint64_t configuration_seed, int configuration) {
  if (options_.layout != "paper") {
    Reset(seed);
    return;
  }
  // The scene comes from the configuration: its plate side alternates (left, right, left, ...)
  // so that 4 demonstrations show both sides, as the paper's 2 + 2 did; its bowl is anywhere.
  Rng scene_rng(configuration_seed);
  mj_resetData(scene_.model(), scene_.data());
  plate_side_ = configuration % 2 == 0 ? 1 : -1;
  PlaceMocap(plate_body_, DrawPlatePosition(plate_side_, scene_rng));
  rng_.Seed(seed);  // the take's own beacon noise and play data
  PlaceToastAndArm();
  PlaceMocap(bowl_body_, DrawBowlPosition(scene_rng));
  FinishReset();
}

std::vector<float> Tabletop::ActionNoiseScale() const {
  std::vector<float> scale(Ur5Arm::kJoints + 1, 1.0f);
  scale[Ur5Arm::kJoints] = 0.0f;  // the gripper command stays the teacher's
  return scale;
}

void Tabletop::ResetToLayout(uint64_t seed, const Eigen::Vector3d& plate,
                             const Eigen::Vector3d& bowl) {
  rng_.Seed(seed);
  mj_resetData(scene_.model(), scene_.data());
  plate_side_ = plate.y() >= 0 ? 1 : -1;
  PlaceMocap(plate_body_, plate);
  PlaceToastAndArm();
  PlaceMocap(bowl_body_, bowl);
  FinishReset();
}

void Tabletop::PlaceToastAndArm() {
  double* toast = scene_.data()->qpos + toast_qpos_;
  toast[0] = kToastX + rng_.Uniform(-kToastJitter, kToastJitter);
  toast[1] = rng_.Uniform(-kToastJitter, kToastJitter);
  toast[2] = kToastRestZ;
  toast[3] = 1.0;
  toast[4] = toast[5] = toast[6] = 0.0;
  arm_->Reset(Ur5Arm::kHome);  // also runs mj_forward
  guarded_->Placed();
}

void Tabletop::FinishReset() {
  mj_forward(scene_.model(), scene_.data());
  grasped_ = false;
  closest_approach_m_ = (arm_->GripPosition() - ToastPosition()).norm();
  closes_on_nothing_ = 0;
  grasps_ = 0;
  holding_toast_ = false;
  CheckReachable();
  Render();
}

void Tabletop::CheckReachable() const {
  const Eigen::Vector3d toast = ToastPosition(), plate = PlatePosition();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const std::vector<Eigen::Vector3d> waypoints = {toast, toast + kApproachHeight_m * up,
                                                  plate + kCarryHeight_m * up,
                                                  plate + kReleaseHeight_m * up};
  for (const Eigen::Vector3d& target : waypoints) {
    if (!arm_->SolveGraspIk(target, 0.0, Ur5Arm::kHome)) {
      char where[96];
      std::snprintf(where, sizeof(where), "(%.3f, %.3f, %.3f)", target.x(), target.y(), target.z());
      throw UserError(std::string("tabletop: the arm cannot reach ") + where +
                      " in this layout (plate at the table edge too far from the robot?)");
    }
  }
}

void Tabletop::Render() {
  if (renderer_ == nullptr) return;  // the "state" observation draws nothing
  image_ = renderer_->Render(scene_, kCamera, options_.image_width, options_.image_height);
}

std::vector<float> Tabletop::ImageAsY() const {
  // RgbImage is rows-first RGB; y is channels first, as the CNN reads it.
  const int h = image_.height, w = image_.width;
  std::vector<float> y(static_cast<size_t>(3) * h * w);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const uint8_t* px = image_.Pixel(r, c);
      for (int ch = 0; ch < 3; ++ch) y[(static_cast<size_t>(ch) * h + r) * w + c] = px[ch];
    }
  }
  return y;
}

Observation Tabletop::Observe() const {
  Observation o;
  // Joint angles relative to the home pose: the task moves each joint by well under a radian
  // around offsets of up to pi, and the policy's tanh layer resolves small numbers better.
  const Ur5Joints q = arm_->JointPositions();
  for (int i = 0; i < Ur5Arm::kJoints; ++i) {
    o.x.push_back(static_cast<float>(q[i] - Ur5Arm::kHome[i]));
  }
  o.x.push_back(static_cast<float>(arm_->GripperOpening()));
  if (options_.observation == "state") {
    for (const Eigen::Vector3d& p : {ToastPosition(), PlatePosition(), BowlPosition()}) {
      o.y.push_back(static_cast<float>(p.x()));
      o.y.push_back(static_cast<float>(p.y()));
    }
  } else {
    o.y = ImageAsY();
  }
  return o;
}

void Tabletop::Step(const std::vector<float>& u) {
  if (static_cast<int>(u.size()) != Ur5Arm::kJoints + 1) {
    throw std::invalid_argument("tabletop action must have 7 entries");
  }
  Ur5Joints qd;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) qd[i] = u[i];
  const bool was_closed = arm_->GripperClosed();
  guarded_->Command(qd);
  guarded_->guard().CommandGripper(u[Ur5Arm::kJoints] > 0.5f);
  AdvanceFrom(was_closed);
}

void Tabletop::Advance() { AdvanceFrom(arm_->GripperClosed()); }

void Tabletop::AdvanceFrom(bool was_closed) {
  guarded_->BeforePeriod();
  arm_->Step(kControlPeriod_s);
  guarded_->AfterPeriod();
  TrackGrasp(was_closed);
  Render();
}

void Tabletop::TrackGrasp(bool was_closed) {
  const bool holding = arm_->HeldObject() == toast_body_;
  if (holding && !holding_toast_) ++grasps_;
  holding_toast_ = holding;
  if (holding) {
    grasped_ = true;
    return;
  }
  if (grasped_) return;  // what happens after the grasp is the plate's part
  const Eigen::Vector3d offset = arm_->GripPosition() - ToastPosition();
  closest_approach_m_ = std::min(closest_approach_m_, offset.norm());
  if (arm_->GripperClosed() && !was_closed) {
    ++closes_on_nothing_;
  }
}

std::vector<float> Tabletop::BeaconReading() {
  if (options_.placement == "none") return {};
  const Eigen::Vector3d beacon = BeaconPosition();
  std::vector<float> b(2);
  for (int k = 0; k < 2; ++k) {
    b[k] = static_cast<float>(beacon[k] + options_.noise_sigma_m * rng_.Normal());
  }
  return b;
}

PlaySample Tabletop::SamplePlay() {
  // The teacher moves the bowl around while the beacon reports the plate; the robot stays put.
  const Eigen::Vector3d bowl = BowlPosition();
  RgbImage scenario_image = std::move(image_);
  PlaceMocap(bowl_body_, DrawBowlPosition(rng_));
  mj_forward(scene_.model(), scene_.data());
  Render();
  const Observation o = Observe();
  PlaySample sample{o.x, o.y, BeaconReading()};
  PlaceMocap(bowl_body_, bowl);
  mj_forward(scene_.model(), scene_.data());
  image_ = std::move(scenario_image);  // the scenario's own frame, as it was
  return sample;
}

double Tabletop::EpisodeMetric() const { return PlanarDistance(ToastPosition(), PlatePosition()); }

WorldTraits Tabletop::Traits() const {
  WorldTraits traits;
  traits.metric_name = "final toast-to-plate distance (m)";
  traits.has_success = true;
  traits.step_seconds = kControlPeriod_s;
  return traits;
}

bool Tabletop::TaskSucceeded() const {
  const Eigen::Vector3d toast = ToastPosition();
  return arm_->HeldObject() != toast_body_ &&
         PlanarDistance(toast, PlatePosition()) < kPlateRadius_m && toast.z() < 0.05;
}

bool Tabletop::DemonstrationDone() const {
  const Eigen::Vector3d retreat = PlatePosition() + Eigen::Vector3d(0, 0, kRetreatHeight_m);
  return TaskSucceeded() && (arm_->GripPosition() - retreat).norm() < kRetreatTolerance_m;
}

bool Tabletop::GoalHoldsAndClear() const {
  if (!TaskSucceeded() || arm_->GripperClosed()) return false;
  const Eigen::Vector3d grip = arm_->GripPosition(), toast = ToastPosition();
  const double toast_top = toast.z() + kToastRestZ;
  return grip.z() - toast_top >= kClearOfToast_m ||
         PlanarDistance(grip, toast) >= kToastRadius_m + kClearOfToast_m;
}

std::map<std::string, double> Tabletop::OutcomeDetails() const {
  const Eigen::Vector3d start(kToastX, 0.0, kToastRestZ);
  const Eigen::Vector3d grip = arm_->GripPosition();
  return {
      {"toast_moved", (ToastPosition() - start).norm() > 0.03 ? 1.0 : 0.0},
      {"toast_held", arm_->HeldObject() == toast_body_ ? 1.0 : 0.0},
      {"grip_nearer_bowl",
       PlanarDistance(grip, BowlPosition()) < PlanarDistance(grip, PlatePosition()) ? 1.0 : 0.0},
      {"toast_to_bowl_m", ToastToBowlDistance()},
      {"grasped", grasped_ ? 1.0 : 0.0},
      {"closest_approach_m", closest_approach_m_},
      {"closes_on_nothing", static_cast<double>(closes_on_nothing_)},
      {"grasps", static_cast<double>(grasps_)},
      // Resting on the table its middle is kToastRestZ up; fallen off, far below.
      {"toast_off_table", ToastPosition().z() < kToastRestZ - kToastOffTableDrop_m ? 1.0 : 0.0},
      {"toast_to_plate_m", EpisodeMetric()}};
}

std::map<std::string, std::array<double, 2>> Tabletop::ObjectLayout() const {
  std::map<std::string, std::array<double, 2>> layout;
  for (const auto& [name, p] :
       {std::pair{"plate", PlatePosition()}, std::pair{"bowl", BowlPosition()},
        std::pair{"toast", ToastPosition()}}) {
    layout[name] = {p.x(), p.y()};
  }
  return layout;
}

double Tabletop::ToastToBowlDistance() const {
  return PlanarDistance(ToastPosition(), BowlPosition());
}

Eigen::Vector3d Tabletop::ToastPosition() const {
  return Vec(scene_.data()->xpos + 3 * toast_body_);
}
Eigen::Vector3d Tabletop::PlatePosition() const {
  return Vec(scene_.data()->mocap_pos + 3 * scene_.model()->body_mocapid[plate_body_]);
}
Eigen::Vector3d Tabletop::BowlPosition() const {
  return Vec(scene_.data()->mocap_pos + 3 * scene_.model()->body_mocapid[bowl_body_]);
}
Eigen::Vector3d Tabletop::BeaconPosition() const {
  return Vec(scene_.data()->site_xpos + 3 * beacon_site_);
}

}  // namespace recon::worlds
