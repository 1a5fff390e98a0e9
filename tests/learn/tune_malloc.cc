// Processes that train must tune malloc once (engine/core/malloc_tuning.h). gtest_main is
// shared with every test executable, so learn_test does it at static initialisation, here once
// for all of its tests.

#include "engine/core/malloc_tuning.h"

namespace {

const bool kMallocTuned = (recon::TuneMallocForTraining(), true);

}  // namespace
