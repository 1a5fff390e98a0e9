#include "app/cli/twin_command.h"

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "app/cli/option_checks.h"
#include "devices/cell/twin_beacon.h"
#include "devices/cell/twin_cell.h"
#include "devices/cell/twin_scene.h"
#include "devices/robot/fake_ur_controller.h"
#include "devices/sim/hidden_uwb_frame.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/rng.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

constexpr uint64_t kPlateBeaconId = 0xDECA0000000000A1ull;
constexpr char kPlateBeaconKey[] = "0xDECA0000000000A1";
// A DWM1001's scatter on a still tag, a few centimetres (the simulated cell's beacons use 2 cm).
constexpr double kBeaconNoise_m = 0.02;
// Seed streams: the hidden frame, the beacon's noise.
constexpr uint64_t kFrameStream = 1, kNoiseStream = 2;

std::atomic<bool> stop_requested{false};

void OnStopSignal(int) { stop_requested = true; }

struct UpFlags {
  std::string dir;
  uint64_t seed = 1;
  double seconds = 0;  ///< 0: until a signal
};

struct MoveFlags {
  std::string dir;
  std::string plate, bowl, toast;
};

/// "X,Y" in metres, on the table. UserError naming the option.
Eigen::Vector2d ParsePlace(const std::string& text, const std::string& option) {
  std::istringstream in(text);
  double x = 0, y = 0;
  char comma = 0;
  if (!(in >> x >> comma >> y) || comma != ',' || !(in >> std::ws).eof()) {
    throw UserError(option + " \"" + text + "\": expected X,Y in metres, e.g. 0.55,0.35");
  }
  const Eigen::Vector2d p(x, y);
  cell::CheckOnTable(p, option);
  return p;
}

void RunUp(const UpFlags& flags) {
  const fs::path dir(flags.dir);
  fs::create_directories(dir);
  const std::string layout_path = (dir / "layout.json").string();
  const cell::TwinLayout layout =
      fs::exists(layout_path) ? cell::ReadTwinLayout(layout_path) : cell::TwinLayout{};
  cell::TwinScene scene;
  scene.Arrange(layout);

  // The beacon beside the plate, as the installation's anchors (a hidden frame) measure it.
  Rng frame_rng(Rng::Derive(flags.seed, kFrameStream));
  cell::TwinBeaconOptions beacon_options;
  beacon_options.node_id = kPlateBeaconId;
  beacon_options.table_to_uwb = sim::DrawHiddenUwbFrame(frame_rng);
  beacon_options.noise_m = kBeaconNoise_m;
  beacon_options.seed = Rng::Derive(flags.seed, kNoiseStream);
  robot::FakeUrController robot;
  cell::TwinBeacon beacon(scene.BeaconPosition(), beacon_options);

  cell::TwinCellDevices devices;
  devices.rtde_port = robot.rtde_port();
  devices.script_port = robot.script_port();
  devices.beacon_ports = {beacon.port()};
  devices.beacon_mode = "lec";
  devices.beacon_names = {{kPlateBeaconKey, "plate"}};
  const std::string profile = cell::WriteTwinCell(dir.string(), devices, layout);
  std::printf(
      "recon twin: a digital twin of a real cell is up (seed %llu)\n"
      "  robot    fake UR controller at 127.0.0.1 (RTDE :%d, script :%d)\n"
      "  beacon   'plate', a fake DWM1001 on %s (lec), through a hidden UWB frame\n"
      "  camera   the tabletop scene drawn at the robot's joints and %s\n"
      "open it:   recon-studio --cell %s --session SESSION_DIR\n"
      "move the objects: recon twin move %s --plate X,Y --bowl X,Y --toast X,Y\n"
      "Ctrl-C stops it.\n",
      static_cast<unsigned long long>(flags.seed), robot.rtde_port(), robot.script_port(),
      beacon.port().c_str(), layout_path.c_str(), profile.c_str(), dir.string().c_str());
  std::fflush(stdout);

  struct sigaction action {};
  action.sa_handler = OnStopSignal;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  const auto started = std::chrono::steady_clock::now();
  std::optional<FileStamp> stamp = StampOf(layout_path);
  while (!stop_requested) {
    if (flags.seconds > 0 && std::chrono::steady_clock::now() - started >=
                                 std::chrono::duration<double>(flags.seconds)) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::optional<FileStamp> now = StampOf(layout_path);
    if (now == stamp) continue;
    stamp = now;
    try {
      scene.Arrange(cell::ReadTwinLayout(layout_path));
      beacon.MoveTo(scene.BeaconPosition());
    } catch (const UserError& e) {
      // A layout edited by hand and broken: say so, keep the last good one.
      std::fprintf(stderr, "recon twin: %s; the objects stay where they were\n", e.what());
    }
  }
  std::printf("recon twin: stopped\n");
}

void RunMove(const MoveFlags& flags) {
  const std::string layout_path = (fs::path(flags.dir) / "layout.json").string();
  if (!fs::exists(layout_path)) {
    throw UserError(flags.dir + " is not a twin (no layout.json): start one with `recon twin up " +
                    flags.dir + "`");
  }
  if (flags.plate.empty() && flags.bowl.empty() && flags.toast.empty()) {
    throw UserError("recon twin move: give --plate, --bowl or --toast");
  }
  cell::TwinLayout layout = cell::ReadTwinLayout(layout_path);
  if (!flags.plate.empty()) layout.plate = ParsePlace(flags.plate, "--plate");
  if (!flags.bowl.empty()) layout.bowl = ParsePlace(flags.bowl, "--bowl");
  if (!flags.toast.empty()) layout.toast = ParsePlace(flags.toast, "--toast");
  cell::WriteTwinLayout(layout_path, layout);
  std::printf("recon twin: plate (%.3f, %.3f), bowl (%.3f, %.3f), toast (%.3f, %.3f)\n",
              layout.plate.x(), layout.plate.y(), layout.bowl.x(), layout.bowl.y(),
              layout.toast.x(), layout.toast.y());
}

}  // namespace

void AddTwinCommand(CLI::App& app) {
  CLI::App* twin = app.add_subcommand(
      "twin",
      "a digital twin of a real cell: the real path (RTDE, serial beacons, a camera) "
      "without hardware");
  twin->require_subcommand(1);

  auto up_flags = std::make_shared<UpFlags>();
  CLI::App* up = twin->add_subcommand(
      "up", "run a fake UR controller and beacon and write DIR/cell.json for recon-studio --cell");
  up->add_option("dir", up_flags->dir, "folder of the twin's profile and layout")->required();
  up->add_option("--seed", up_flags->seed, "the hidden UWB frame and the beacon's noise")
      ->check(SeedNumber())
      ->capture_default_str();
  // An explicit 0 is refused rather than read as "forever": a person who types a duration
  // expects it to end.
  up->add_option("--seconds", up_flags->seconds, "stop after this long (default: until Ctrl-C)")
      ->check(PositiveNumberUpTo(1e7));
  up->callback([up_flags] { RunUp(*up_flags); });

  auto move_flags = std::make_shared<MoveFlags>();
  CLI::App* move = twin->add_subcommand("move", "move the twin's objects (rewrites its layout)");
  move->add_option("dir", move_flags->dir, "the twin's folder")->required();
  move->add_option("--plate", move_flags->plate, "the plate's table X,Y in metres");
  move->add_option("--bowl", move_flags->bowl, "the bowl's table X,Y in metres");
  move->add_option("--toast", move_flags->toast, "the toast's table X,Y in metres");
  move->callback([move_flags] { RunMove(*move_flags); });
}

}  // namespace recon::cli
