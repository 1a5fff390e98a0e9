#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/teach/simulated_person.h"
#include "engine/worlds/tabletop.h"

namespace recon::teach {

/// What a run of takes by a simulated person cost, as a teacher's ledger counts it.
struct PersonTakeStats {
  int demonstrations = 0;    ///< takes kept
  int tries = 0;             ///< takes recorded, the discarded ones included
  int kept_done = 0;         ///< kept takes in which the task was done
  int grasp_attempts = 0;    ///< closes of the gripper over the toast, over every try
  double kept_seconds = 0;   ///< recorded seconds of the kept takes
  double total_seconds = 0;  ///< recorded seconds of every try
  int still_samples = 0;     ///< kept samples in which the arm was told to stand still
  int kept_samples = 0;
  double longest_kept_seconds = 0;
};

/// A person's demonstrations of one run, as a teacher gives them in the studio: take i in the
/// scene ResetForDemo gives it (the session's protocol), recorded by `style`'s person; a take in
/// which the task was not done is discarded and recorded again in the same scene, up to
/// `max_tries` tries, the last kept whatever it shows. Play samples as RecordDemonstrations
/// draws them (from each demonstration's scene, before it runs). Every choice of the person
/// comes from `person_seed` and the take's seed and try. Takes end where a person ends them
/// (World::GoalHoldsAndClear).
Dataset RecordPersonDemonstrations(worlds::Tabletop& world, const std::vector<uint64_t>& seeds,
                                   int play_per_scenario, uint64_t person_seed,
                                   const PersonStyle& style = {}, int max_tries = 5,
                                   PersonTakeStats* stats = nullptr);

}  // namespace recon::teach
