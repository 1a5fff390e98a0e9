// Speed of "what does it look at" (issue 18) on the tabletop, 2 cores:
//
//   ninja -C build/release probe_bench && build/release/bench/probe_bench
//
// BM_ProbeTabletop10x10TwoMethods: the whole probe of `recon eval --probe` but the files: every
//   object (plate, bowl, toast) moved over a 10 x 10 grid of the table, each place rendered once
//   and both methods' actions and features computed, then the read-out's 60 test scenes
//   rendered and both methods' features read out (the issue: under 20 s).
// BM_OutcomeProbeTabletop5x5TwoMethods: `--probe --outcome`'s rollouts alone: the bowl moved over
//   a 5 x 5 grid and both methods rolled out whole from every free place (no target: a rollout
//   costs an episode of steps, each rendered).
// BM_SaliencyGradient64: the input-gradient saliency of one 64 x 64 frame (the issue: under
//   50 ms). BM_SaliencyOcclusion64: the occlusion map of one frame (8 px patches, stride 4).
// The policies have the tabletop recipe's networks at a fixed seed's initial weights: speed does
// not depend on what they learned.

#include <benchmark/benchmark.h>

#include <memory>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/rng.h"
#include "engine/experiments/evaluation.h"
#include "engine/experiments/recipe.h"
#include "engine/learn/architecture.h"
#include "engine/learn/policy_impl.h"
#include "engine/learn/target_scaling.h"
#include "engine/probe/distractor_probe.h"
#include "engine/probe/feature_readout.h"
#include "engine/probe/outcome_probe.h"
#include "engine/probe/saliency.h"
#include "engine/worlds/tabletop.h"

namespace recon::probe {
namespace {

std::unique_ptr<worlds::Tabletop> MakeTabletop() {
  worlds::TabletopOptions options;
  options.placement = "none";
  return std::make_unique<worlds::Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

learn::Policy RecipePolicy(const DataSpec& spec, learn::Method method, uint64_t seed) {
  const learn::NetworkConfig network =
      experiments::RecipeForWorld("tabletop", /*images_are_bytes=*/true).network;
  const learn::Architecture arch = learn::BuildArchitecture(spec, network, method);
  std::vector<float> params(static_cast<size_t>(arch.num_params));
  Rng rng(seed);
  learn::InitializeParameters(arch, rng, params.data());
  return learn::Policy(
      std::make_shared<learn::PolicyImpl>(arch, params, learn::TargetScaling::Identity(spec)));
}

ProbeSubject Subject(const learn::Policy& policy, const std::string& method) {
  ProbeSubject subject;
  subject.rollouts = [policy](uint64_t seed, size_t copies,
                              const ProbeSubject::Arrangement& arrange) {
    const std::vector<experiments::ScenarioOutcome> outcomes = experiments::EvaluatePolicy(
        [] { return std::unique_ptr<worlds::World>(MakeTabletop()); }, policy,
        std::vector<uint64_t>(copies, seed), false, {},
        [&arrange](worlds::World& w, size_t copy) { arrange(w, copy); });
    std::vector<bool> succeeded;
    for (const experiments::ScenarioOutcome& o : outcomes) succeeded.push_back(o.succeeded);
    return succeeded;
  };
  subject.method = subject.label = method;
  subject.act = [policy](const ProbeSubject::Rows& xs, const ProbeSubject::Rows& ys) {
    return policy.ActBatch(xs, ys);
  };
  subject.features = [policy](const ProbeSubject::Rows& xs, const ProbeSubject::Rows& ys) {
    return policy.FeaturesBatch(xs, ys);
  };
  return subject;
}

void BM_ProbeTabletop10x10TwoMethods(benchmark::State& state) {
  auto world = MakeTabletop();
  DataSpec spec = world->Spec();
  spec.b_dim = 2;  // RECON's beacon net reads the plate
  const std::vector<ProbeSubject> subjects = {
      Subject(RecipePolicy(spec, learn::Method::kBaseline, 1), "baseline"),
      Subject(RecipePolicy(spec, learn::Method::kRecon, 2), "recon")};
  std::vector<uint64_t> seeds;
  for (uint64_t i = 0; i < 60; ++i) seeds.push_back(Rng::Derive(99, i));
  for (auto _ : state) {
    ProbeResult result = ProbeObjects(*world, 7, {}, ProbeGrid{}, subjects);
    const SceneFrames frames = RenderScenes(*world, seeds);
    for (const ProbeSubject& s : subjects) benchmark::DoNotOptimize(ReadOutObjects(s, frames));
    benchmark::DoNotOptimize(result);
  }
  state.counters["probe_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ProbeTabletop10x10TwoMethods)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_OutcomeProbeTabletop5x5TwoMethods(benchmark::State& state) {
  auto world = MakeTabletop();
  DataSpec spec = world->Spec();
  spec.b_dim = 2;
  const std::vector<ProbeSubject> subjects = {
      Subject(RecipePolicy(spec, learn::Method::kBaseline, 1), "baseline"),
      Subject(RecipePolicy(spec, learn::Method::kRecon, 2), "recon")};
  ProbeGrid grid;
  grid.nx = grid.ny = 5;
  int places = 0;
  for (auto _ : state) {
    const OutcomeResult result = ProbeOutcomes(*world, 7, {"bowl"}, grid, subjects);
    places = result.outcomes[0][0].places;
    benchmark::DoNotOptimize(result);
  }
  state.counters["outcome_probe_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["places"] = places;
}
BENCHMARK(BM_OutcomeProbeTabletop5x5TwoMethods)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

/// One frame of a tabletop scene and a RECON policy of the recipe's shape.
struct SaliencyCase {
  worlds::Observation seen;
  learn::Policy policy;
};

SaliencyCase MakeSaliencyCase() {
  auto world = MakeTabletop();
  world->Reset(7);
  DataSpec spec = world->Spec();
  spec.b_dim = 2;
  return {world->Observe(), RecipePolicy(spec, learn::Method::kRecon, 2)};
}

void BM_SaliencyGradient64(benchmark::State& state) {
  const SaliencyCase c = MakeSaliencyCase();
  for (auto _ : state) benchmark::DoNotOptimize(GradientSaliency(c.policy, c.seen.x, c.seen.y));
}
BENCHMARK(BM_SaliencyGradient64)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SaliencyOcclusion64(benchmark::State& state) {
  const SaliencyCase c = MakeSaliencyCase();
  for (auto _ : state) {
    benchmark::DoNotOptimize(OcclusionSaliency(c.policy, c.seen.x, c.seen.y, 8, 4));
  }
}
BENCHMARK(BM_SaliencyOcclusion64)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace recon::probe

BENCHMARK_MAIN();
