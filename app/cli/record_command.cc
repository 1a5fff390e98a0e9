#include "app/cli/record_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/option_checks.h"
#include "app/cli/session_world.h"
#include "devices/cell/sim_calibration.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/core/progress.h"
#include "engine/core/strings.h"
#include "engine/store/session.h"
#include "engine/teach/recorder.h"
#include "engine/teach/session_setup.h"
#include "engine/worlds/world_factory.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

struct RecordFlags {
  std::string session;
  std::string world;
  std::string placement;
  int demos = 5;
  int play = 0;
  uint64_t seed = 1;
  int image_size = 64;
  double noise = 0.0;
  double demo_noise = 0.0;  ///< only when --demo-noise is given; else the world's default
  std::string layout;
  std::string calibration;
  bool no_calibration = false;
  std::string rerecord;
};

std::string Plural(int64_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

/// A new simulated arm cell is calibrated before teaching, as a lab would: the simulated
/// calibration (AprilTag ground truth against DWM1001 lines) runs and is attached.
void CalibrateNewCell(store::Session& session, uint64_t seed) {
  cell::SimCalibrationOptions options;
  options.seed = seed;
  std::printf("calibrating the simulated cell's UWB frame (%d beacon poses, seed %llu)\n",
              options.points, static_cast<unsigned long long>(seed));
  std::fflush(stdout);
  ProgressLine progress("calibrating", options.points);
  const cell::SimCalibrationResult result =
      cell::RunSimulatedCalibration(options, [&](int, int) { progress.Advance(); });
  progress.Finish();
  for (const Eigen::Vector2d& p : result.replaced_unseen) {
    std::printf("calibration: the camera did not see the beacon's tag at (%.3f, %.3f); moved it\n",
                p.x(), p.y());
  }
  const std::string path = (fs::path(session.dir()) / "calibration.json").string();
  calib::SaveCalibration(result.report, path);
  session.AttachCalibration(path);
  std::printf("calibration: RMSE %.4f m over %d points, %s\n", result.report.rmse_m,
              result.report.num_inliers, result.report.passed ? "PASS" : "FAIL");
}

void RunRecord(const RecordFlags& flags, const CLI::App& command) {
  const bool exists = store::Session::Exists(flags.session);
  if (!flags.rerecord.empty() && !exists) {
    throw UserError("--rerecord needs an existing session; " + flags.session + " is not one");
  }
  std::optional<store::Session> session;
  teach::SessionSetup setup;
  if (exists) {
    // Appending: the session decides the world; flags given must agree with it.
    session.emplace(store::Session::Open(flags.session));
    const store::SessionManifest& m = session->manifest();
    setup.world_name = flags.world.empty() ? m.world : flags.world;
    setup.placement = flags.placement.empty() ? m.placement : flags.placement;
    setup.image_size = command.count("--image-size") > 0 ? flags.image_size : m.image_size;
    setup.seed = command.count("--seed") > 0 ? flags.seed : m.seed;
    setup.layout = flags.layout.empty() ? m.layout : flags.layout;
    teach::CheckSessionMatches(m, setup);
    for (const char* option : {"--noise", "--demo-noise"}) {
      if (command.count(option) > 0) {
        throw UserError(std::string(option) + " is fixed when a session is created; " +
                        flags.session + " already records with its own (session.json)");
      }
    }
    if (session->recovered_temporaries() > 0) {
      std::printf("removed %d unfinished episode file(s) left by an interrupted recording\n",
                  session->recovered_temporaries());
    }
    setup.beacon_noise_sigma = m.beacon_noise_sigma;
  } else {
    NewSessionOptions options;
    options.world = flags.world;
    options.placement = flags.placement;
    options.layout = flags.layout;
    if (command.count("--noise") > 0) options.beacon_noise = flags.noise;
    if (command.count("--demo-noise") > 0) options.demo_noise = flags.demo_noise;
    options.image_size = flags.image_size;
    options.seed = flags.seed;
    setup = NewSessionSetup(options, flags.session);
  }
  const std::unique_ptr<worlds::World> world = MakeSetupWorld(setup);
  {
    const int n = world->DemosPerConfiguration();
    if (n > 1) {
      const int first = exists ? session->NextDemoNumber() : 0, last = first + flags.demos - 1;
      if ((last + 1) % n != 0 && flags.demos > 0) {
        throw UserError("--demos " + std::to_string(flags.demos) + ": the " + setup.world_name +
                        " " + setup.layout + " layout records " + std::to_string(n) +
                        " demonstrations per configuration, and the session would end with "
                        "configuration " +
                        std::to_string(last / n) + " having " + std::to_string((last + 1) % n) +
                        " of them; record " + std::to_string(flags.demos + n - (last + 1) % n) +
                        " instead");
      }
      if (flags.demos > 0) {
        std::printf(
            "demonstrations demo_%d..demo_%d are takes of configurations %d..%d (%d per "
            "configuration: plate side and bowl place)\n",
            first, last, first / n, last / n, n);
      }
    }
  }
  if (!exists) {
    session.emplace(
        store::Session::Create(flags.session, teach::NewSessionManifest(setup, *world)));
    std::printf("new session %s: %s, beacons: %s\n", flags.session.c_str(),
                setup.world_name.c_str(), setup.placement.c_str());
    if (!flags.calibration.empty()) {
      session->AttachCalibration(flags.calibration);
    } else if (!flags.no_calibration && setup.world_name != "dynamic2d" &&
               setup.world_name != "dynamic2d-state" && setup.world_name != "static2d") {
      CalibrateNewCell(*session, setup.seed);
    }
  } else if (!flags.calibration.empty()) {
    session->AttachCalibration(flags.calibration);
  }

  if (!flags.rerecord.empty()) {
    const store::EpisodeEntry& entry = teach::ReRecordDemo(*session, *world, flags.rerecord);
    std::printf("re-recorded %s (scenario seed %llu, %lld samples); the old take is in %s/trash/\n",
                entry.name.c_str(), static_cast<unsigned long long>(entry.meta.seed),
                static_cast<long long>(entry.meta.num_samples), flags.session.c_str());
    return;
  }
  std::printf("recording %s and %s into %s (%s, scenario seeds derived from %llu)\n",
              Plural(flags.demos, "demonstration").c_str(),
              Plural(flags.play, "play sample").c_str(), flags.session.c_str(),
              setup.world_name.c_str(), static_cast<unsigned long long>(setup.seed));
  std::fflush(stdout);
  ProgressLine progress("recording", flags.demos + flags.play);
  int last_units = 0;
  teach::RecordPlan plan;
  plan.demos = flags.demos;
  plan.play_samples = flags.play;
  plan.seed = setup.seed;
  teach::RecordIntoSession(*session, *world, plan, [&](const teach::RecordProgress& p) {
    const int units = p.demos_done + p.play_samples_done;
    progress.Advance(units - last_units, "committed " + p.last_committed);
    last_units = units;
  });
  progress.Finish();

  int64_t samples = 0;
  for (const store::EpisodeEntry& e : session->demos()) samples += e.meta.num_samples;
  std::printf("session %s now holds %s (%lld samples, %.1f s of teaching) and %lld play samples\n",
              flags.session.c_str(), Plural(session->demos().size(), "demonstration").c_str(),
              static_cast<long long>(samples), session->DemoSeconds(),
              static_cast<long long>(session->PlaySamples()));
}

}  // namespace

void AddRecordCommand(CLI::App& app) {
  auto flags = std::make_shared<RecordFlags>();
  CLI::App* record = app.add_subcommand(
      "record", "record demonstrations and play data with the scripted teleop into a session");
  record->add_option("--session", flags->session, "session folder (created if new)")->required();
  record->add_option("--world", flags->world,
                     "the cell's task for a new session: " + JoinNames(worlds::WorldNames()));
  record->add_option("--placement", flags->placement,
                     "beacon placement for a new session (default: the paper's RECON one)");
  record->add_option("--demos", flags->demos, "demonstrations to record")
      ->check(WholeBetween(0, kMaxDemos))
      ->capture_default_str();
  record->add_option("--play", flags->play, "play samples to record")
      ->check(WholeBetween(0, kMaxPlay))
      ->capture_default_str();
  record
      ->add_option("--seed", flags->seed,
                   "scenario seeds of new episodes derive from this and their numbers "
                   "(default: the session's)")
      ->check(SeedNumber())
      ->capture_default_str();
  record->add_option("--image-size", flags->image_size, "camera images are N x N (tabletop)")
      ->check(WholeBetween(16, 480))
      ->capture_default_str();
  record
      ->add_option("--noise", flags->noise,
                   "beacon noise sigma per axis for a new session (default: a DWM1001's 0.07 m "
                   "on the tabletop, 0 elsewhere)")
      ->check(NumberBetween(0, kMaxBeaconNoise_m));
  record
      ->add_option("--demo-noise", flags->demo_noise,
                   "noise injected into the executed joint velocities while demonstrating, for a "
                   "new session (DART; rad/s; 0 = off, the default)")
      ->check(NumberBetween(0, kMaxDemoNoise_rad_s));
  record->add_option("--layout", flags->layout,
                     "scene layout of a new tabletop session: paper (default: the plate at one "
                     "of two places, 2 demonstrations per configuration) or wide");
  record->add_option("--calibration", flags->calibration,
                     "attach this calibration (from `recon calibrate --out`)");
  record->add_option("--rerecord", flags->rerecord,
                     "record demonstration demo_N again in its own scene, replacing it (the old "
                     "take moves to trash/)");
  record->add_flag("--no-calibration", flags->no_calibration,
                   "do not calibrate a new simulated arm cell");
  record->callback([flags, record] { RunRecord(*flags, *record); });
}

}  // namespace recon::cli
