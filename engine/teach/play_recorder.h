#pragma once

#include <cstdint>
#include <string>

#include "engine/store/episode_file.h"
#include "engine/worlds/world.h"

namespace recon::teach {

/// Records play data one sample at a time: the teacher moves the objects about while the beacons
/// report (World::SamplePlay), and the studio shows each sample as it is taken.
/// RecordSessionPlayChunk (`recon record --play`) ticks the same recorder in a loop, so both
/// record the same samples for the same seed.
class PlayRecorder {
 public:
  /// `source` names the recording in the chunk's metadata, e.g. "simulated-play".
  PlayRecorder(worlds::World& world, std::string source);

  /// Resets the world to scenario `seed` and starts a chunk of `count` samples (count >= 1).
  void Start(uint64_t seed, int count);
  /// The same in a configuration's scene (World::ResetTake): the objects where `configuration`
  /// (drawn from `configuration_seed`) puts them, `seed` driving the rest (the play moves and
  /// the beacon noise).
  void StartTake(uint64_t seed, uint64_t configuration_seed, int configuration, int count);
  /// Draws one sample. Returns false once the chunk is complete.
  bool Tick();
  bool recording() const { return recording_; }
  int samples() const { return static_cast<int>(record_.samples.size()); }
  int target() const { return target_; }
  /// The latest sample (nullptr before the first).
  const PlaySample* last() const {
    return record_.samples.empty() ? nullptr : &record_.samples.back();
  }
  /// Ends the chunk (if still running) and hands it over, with its metadata.
  store::PlayRecord Take();

 private:
  worlds::World& world_;
  std::string source_;
  store::PlayRecord record_;
  int target_ = 0;
  bool recording_ = false;
};

}  // namespace recon::teach
