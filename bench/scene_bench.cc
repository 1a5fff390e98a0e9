// Speed of the simulated cell's bin-transfer world against MuJoCo itself, on the same model:
//
//   ninja -C build/release scene_bench && build/release/bench/scene_bench
//
// BM_BareMjStep: mj_step on the settled bin-transfer scene; mj_steps_per_s is the physics ceiling.
// BM_BinTransferStep: one 0.1 s control step (50 mj_steps, the scripted gripper checked every
//   20 ms) with the expert acting; a new scenario every episode (reset time excluded).
//   mj_steps_per_s compares directly with the bare loop; sim_s_per_s is the real-time factor.
// BM_BinTransferReset: drawing, dropping and settling a layout plus the expert's IK.
// BM_RecordDemonstration: what `recon record` pays per demonstration: reset, 3 play samples and
//   a 60-step expert episode; sim_s_per_s counts the episode's simulated time.
// Rates are per CPU second (Google Benchmark's default), which stays comparable when other jobs
// share the two cores; the Time column is wall time.

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <cstdint>

#include "engine/worlds/bintransfer.h"
#include "engine/worlds/world.h"

namespace recon::worlds {
namespace {

void BM_BareMjStep(benchmark::State& state) {
  BinTransfer world("position", 0.0);
  world.Reset(0);
  const mjModel* m = world.scene().model();
  mjData* d = world.scene().data();
  for (auto _ : state) mj_step(m, d);
  const double steps = static_cast<double>(state.iterations());
  state.counters["mj_steps_per_s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["sim_s_per_s"] =
      benchmark::Counter(steps * m->opt.timestep, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BareMjStep);

void BM_BinTransferStep(benchmark::State& state) {
  BinTransfer world("position", 0.0);
  uint64_t seed = 0;
  world.Reset(seed);
  for (auto _ : state) {
    if (world.Steps() == world.EpisodeLength()) {
      state.PauseTiming();
      world.Reset(++seed);
      state.ResumeTiming();
    }
    world.Step(world.ExpertAction());
  }
  const double steps = static_cast<double>(state.iterations());
  const double substeps = BinTransfer::kControlPeriod_s / world.scene().model()->opt.timestep;
  state.counters["control_steps_per_s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["mj_steps_per_s"] =
      benchmark::Counter(steps * substeps, benchmark::Counter::kIsRate);
  state.counters["sim_s_per_s"] =
      benchmark::Counter(steps * BinTransfer::kControlPeriod_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BinTransferStep);

void BM_BinTransferReset(benchmark::State& state) {
  BinTransfer world("position", 0.0);
  uint64_t seed = 0;
  for (auto _ : state) world.Reset(++seed);
  state.counters["resets_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BinTransferReset);

void BM_RecordDemonstration(benchmark::State& state) {
  BinTransfer world("position", 0.0);
  uint64_t seed = 0;
  for (auto _ : state) {
    Dataset data = RecordDemonstrations(world, {++seed}, world.PlaySamplesPerScenario());
    benchmark::DoNotOptimize(data);
  }
  const double demos = static_cast<double>(state.iterations());
  state.counters["demos_per_s"] = benchmark::Counter(demos, benchmark::Counter::kIsRate);
  state.counters["sim_s_per_s"] = benchmark::Counter(
      demos * world.EpisodeLength() * BinTransfer::kControlPeriod_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RecordDemonstration)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace recon::worlds

BENCHMARK_MAIN();
