#include "engine/teach/person_takes.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/worlds/world.h"

namespace recon::teach {

namespace {

// A sample in which every joint velocity is zero: the arm told to stand still.
bool Still(const Sample& sample) {
  for (size_t i = 0; i + 1 < sample.u.size(); ++i) {
    if (sample.u[i] != 0.0f) return false;
  }
  return true;
}

}  // namespace

Dataset RecordPersonDemonstrations(worlds::Tabletop& world, const std::vector<uint64_t>& seeds,
                                   int play_per_scenario, uint64_t person_seed,
                                   const PersonStyle& style, int max_tries,
                                   PersonTakeStats* stats) {
  if (play_per_scenario < 0) {
    throw UserError("play samples per scenario must be >= 0, got " +
                    std::to_string(play_per_scenario));
  }
  if (max_tries < 1) throw UserError("a person needs at least one try per take");
  Dataset dataset;
  dataset.spec = world.Spec();
  PersonTakeStats local;
  PersonTakeStats& s = stats != nullptr ? *stats : local;
  SimulatedPerson person(style);
  const double step_s = world.StepSeconds();
  for (size_t index = 0; index < seeds.size(); ++index) {
    Episode kept;
    for (int attempt = 0; attempt < max_tries; ++attempt) {
      worlds::ResetForDemo(world, seeds, index);
      if (attempt == 0) {
        for (int i = 0; i < play_per_scenario; ++i) dataset.play.push_back(world.SamplePlay());
        if (play_per_scenario > 0) dataset.play_chunks.push_back(play_per_scenario);
      }
      // The recorder's own reset would draw the scene again; the person's take starts here.
      person.StartTake(world, Rng::Derive(Rng::Derive(person_seed, seeds[index]), attempt));
      Episode episode;
      for (int t = 0; t < world.EpisodeLength(); ++t) {
        worlds::Observation obs = world.Observe();
        Sample sample;
        sample.x = std::move(obs.x);
        sample.y = std::move(obs.y);
        sample.b = world.BeaconReading();
        const TeleopCommand command = person.Next(world);
        sample.u = CartesianTeleopAction(world, command);
        world.Step(sample.u);
        episode.samples.push_back(std::move(sample));
        if (command.finish || world.GoalHoldsAndClear()) break;
      }
      ++s.tries;
      s.grasp_attempts += person.grasp_attempts();
      s.total_seconds += static_cast<double>(episode.samples.size()) * step_s;
      const bool done = world.TaskSucceeded();
      kept = std::move(episode);
      if (done) {
        ++s.kept_done;
        break;
      }
    }
    ++s.demonstrations;
    const double seconds = static_cast<double>(kept.samples.size()) * step_s;
    s.kept_seconds += seconds;
    s.longest_kept_seconds = std::max(s.longest_kept_seconds, seconds);
    s.kept_samples += static_cast<int>(kept.samples.size());
    for (const Sample& sample : kept.samples) s.still_samples += Still(sample) ? 1 : 0;
    dataset.demos.push_back(std::move(kept));
  }
  return dataset;
}

}  // namespace recon::teach
