#include "app/cli/session_repair.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/option_checks.h"
#include "app/cli/session_world.h"
#include "engine/core/strings.h"
#include "engine/store/session.h"
#include "engine/worlds/world_factory.h"

namespace recon::cli {

namespace {

struct RepairFlags {
  std::string dir;
  NewSessionOptions options;
  double noise = 0;
  double demo_noise = 0;
};

void RunRepair(const RepairFlags& flags, const CLI::App& command) {
  NewSessionOptions options = flags.options;
  if (command.count("--noise") > 0) options.beacon_noise = flags.noise;
  if (command.count("--demo-noise") > 0) options.demo_noise = flags.demo_noise;
  const teach::SessionSetup setup = NewSessionSetup(options, flags.dir);
  const std::unique_ptr<worlds::World> world = MakeSetupWorld(setup);
  const store::Session session =
      store::Session::Repair(flags.dir, teach::NewSessionManifest(setup, *world));
  std::printf(
      "repaired %s: a new session.json for %s (beacons: %s%s%s) over %zu demonstration(s) and "
      "%zu play chunk(s), every one checked against it\n",
      flags.dir.c_str(), setup.world_name.c_str(), setup.placement.c_str(),
      setup.layout.empty() ? "" : ", layout ", setup.layout.c_str(), session.demos().size(),
      session.play_chunks().size());
  int damaged = 0;
  for (const auto* list : {&session.demos(), &session.play_chunks()}) {
    for (const store::EpisodeEntry& e : *list) damaged += e.problem.empty() ? 0 : 1;
  }
  if (damaged > 0) {
    std::printf(
        "%d episode file(s) cannot be read and stay listed as damaged (see `recon session "
        "info %s`)\n",
        damaged, flags.dir.c_str());
  }
  std::printf(
      "episode files do not record these, so they are what you gave (or the world's defaults): "
      "beacon noise %g m, injected demonstration noise %g, seed %llu. The lost manifest's "
      "episode flags (bad marks, splits, notes) are back to their defaults: mark again with "
      "`recon session mark %s ...`\n",
      setup.beacon_noise_sigma, setup.demo_noise_sigma, static_cast<unsigned long long>(setup.seed),
      flags.dir.c_str());
}

}  // namespace

void AddSessionRepairCommand(CLI::App& session) {
  auto flags = std::make_shared<RepairFlags>();
  CLI::App* repair = session.add_subcommand(
      "repair", "give a session folder that lost its session.json a new one, from its episodes");
  repair->add_option("dir", flags->dir, "session folder")->required();
  repair
      ->add_option("--world", flags->options.world,
                   "the world its episodes were recorded in: " + JoinNames(worlds::WorldNames()))
      ->required();
  repair->add_option("--placement", flags->options.placement,
                     "beacon placement it was taught with (default: the paper's RECON one)");
  repair->add_option("--layout", flags->options.layout, "its scene layout (tabletop: paper, wide)");
  repair->add_option("--image-size", flags->options.image_size, "its camera images' N (N x N)")
      ->check(WholeBetween(16, 480))
      ->capture_default_str();
  repair->add_option("--seed", flags->options.seed, "its scenario seed")
      ->check(SeedNumber())
      ->capture_default_str();
  repair->add_option("--noise", flags->noise, "its beacon noise sigma per axis (m)")
      ->check(NumberBetween(0, kMaxBeaconNoise_m));
  repair->add_option("--demo-noise", flags->demo_noise, "its injected demonstration noise (rad/s)")
      ->check(NumberBetween(0, kMaxDemoNoise_rad_s));
  repair->callback([flags, repair] { RunRepair(*flags, *repair); });
}

}  // namespace recon::cli
