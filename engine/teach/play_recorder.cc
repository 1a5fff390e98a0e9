#include "engine/teach/play_recorder.h"

#include "engine/core/error.h"

namespace recon::teach {

PlayRecorder::PlayRecorder(worlds::World& world, std::string source)
    : world_(world), source_(std::move(source)) {}

void PlayRecorder::Start(uint64_t seed, int count) { StartTake(seed, seed, -1, count); }

void PlayRecorder::StartTake(uint64_t seed, uint64_t configuration_seed, int configuration,
                             int count) {
  if (count < 1)
    throw UserError("a play chunk needs at least one sample, not " + std::to_string(count));
  if (configuration < 0) {
    world_.Reset(seed);
  } else {
    world_.ResetTake(seed, configuration_seed, configuration);
  }
  record_ = {};
  record_.meta.kind = "play";
  record_.meta.seed = seed;
  record_.meta.source = source_;
  record_.meta.recorded_at = store::NowIso8601();
  record_.samples.reserve(count);
  target_ = count;
  recording_ = true;
}

bool PlayRecorder::Tick() {
  if (!recording_) return false;
  record_.samples.push_back(world_.SamplePlay());
  if (samples() >= target_) recording_ = false;
  return recording_;
}

store::PlayRecord PlayRecorder::Take() {
  recording_ = false;
  record_.meta.num_samples = samples();
  // The experiments' accounting: a play sample costs the teacher one control period.
  record_.meta.teaching_seconds = samples() * world_.StepSeconds();
  return std::move(record_);
}

}  // namespace recon::teach
