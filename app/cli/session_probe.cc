#include "app/cli/session_probe.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>

#include "app/cli/result_staleness.h"
#include "app/cli/session_training.h"
#include "app/cli/session_world.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/rng.h"
#include "engine/experiments/evaluation.h"
#include "engine/learn/learner.h"
#include "engine/probe/feature_readout.h"
#include "engine/probe/outcome_probe.h"
#include "engine/probe/recorded_readout.h"
#include "engine/report/heat_map.h"
#include "engine/store/training_record.h"

namespace recon::cli {

namespace fs = std::filesystem;

namespace {

/// The read-out's scenes come from their own stream of the test seed: never the scenes taught,
/// and not the probed scene either.
constexpr uint64_t kReadoutStream = 0x72656164;  // "read"
constexpr int kMinReadoutScenes = 8;             // one in four held out: at least 2
constexpr int kMaxReadoutScenes = 2000;          // their frames are held at once (about 50 kB each)

constexpr int kMaxRecordedFrames = 2000;

probe::ProbeSubject Subject(const std::string& method, const std::string& label,
                            const learn::Policy& policy, const store::SessionManifest& manifest) {
  probe::ProbeSubject subject;
  subject.method = method;
  subject.label = label;
  subject.act = [policy](const probe::ProbeSubject::Rows& xs, const probe::ProbeSubject::Rows& ys) {
    return policy.ActBatch(xs, ys);
  };
  subject.features = [policy](const probe::ProbeSubject::Rows& xs,
                              const probe::ProbeSubject::Rows& ys) {
    return policy.FeaturesBatch(xs, ys);
  };
  subject.rollouts = [policy, manifest](uint64_t scene_seed, size_t copies,
                                        const probe::ProbeSubject::Arrangement& arrange) {
    const std::vector<experiments::ScenarioOutcome> outcomes = experiments::EvaluatePolicy(
        [&manifest] { return MakeSessionWorld(manifest, "none"); }, policy,
        std::vector<uint64_t>(copies, scene_seed), false, {},
        [&arrange](worlds::World& world, size_t copy) { arrange(world, copy); });
    std::vector<bool> succeeded;
    for (const experiments::ScenarioOutcome& o : outcomes) succeeded.push_back(o.succeeded);
    return succeeded;
  };
  return subject;
}

/// One heat map per method and object into the session, each object's maps on one scale.
void WriteHeatMaps(const store::Session& session, store::ProbeSummary& summary) {
  EnsureWritableDirectory(fs::path(session.ProbeSummaryPath()).parent_path().string());
  for (auto& [method, probed] : summary.methods) {
    for (auto& [object, o] : probed.objects) {
      if (o.action_change.empty()) continue;  // read out only: no map
      // Wide, as the table is from behind the robot (1 m across, 0.6 m deep).
      report::WriteChart(ProbeHeatMap(summary, method, object),
                         session.ProbeFigurePath(method, object), 720, 470);
      o.figure = store::Session::ProbeFigureRelativePath(method, object);
      if (!o.outcome.empty()) {
        report::WriteChart(ProbeOutcomeMap(summary, method, object),
                           session.ProbeFigurePath(method, object + "_outcome"), 720, 470);
        o.outcome_figure = store::Session::ProbeFigureRelativePath(method, object + "_outcome");
      }
    }
  }
}

/// The methods to probe, loaded, and the summary's entries for them.
std::vector<probe::ProbeSubject> LoadSubjects(const store::Session& session,
                                              const std::vector<std::string>& methods,
                                              store::ProbeSummary& summary) {
  std::vector<probe::ProbeSubject> subjects;
  for (const std::string& method : methods) {
    const std::string label = MethodLabel(session, method);
    subjects.push_back(Subject(method, label, learn::LoadPolicy(session.CheckpointPath(method)),
                               session.manifest()));
    store::ProbedMethod& probed = summary.methods[method];
    probed.label = label;
    const std::string model_id = CheckpointModelId(session.CheckpointPath(method));
    if (!model_id.empty()) probed.model_id = model_id;
  }
  return subjects;
}

/// A real cell's session: each method's features read out on its recorded frames against the
/// beacons' readings (nothing to move: the cell cannot be simulated).
void ReadOutRecordedFrames(const store::Session& session,
                           const std::vector<probe::ProbeSubject>& subjects,
                           store::ProbeSummary& summary) {
  const store::SessionManifest& manifest = session.manifest();
  std::vector<std::string> objects;  // what each beacon marks
  for (const BeaconSpec& beacon : manifest.beacons) {
    const auto assigned = manifest.beacon_assignments.find(beacon.name);
    objects.push_back(assigned != manifest.beacon_assignments.end() ? assigned->second
                                                                    : beacon.name);
  }
  store::DatasetOptions every;
  every.split = store::Split::kAll;
  const Dataset data = session.LoadDataset(every);
  const probe::RecordedFrames frames =
      probe::SampleRecordedFrames(data, manifest.beacons, objects, kMaxRecordedFrames);
  summary.readout_frames = static_cast<int>(frames.xs.size());
  summary.readout_episodes = frames.episode_count;
  for (const probe::ProbeSubject& subject : subjects) {
    store::ProbedMethod& probed = summary.methods[subject.method];
    for (const auto& [object, score] : probe::ReadOutRecorded(subject, frames)) {
      store::ProbedObject& o = probed.objects[object];
      if (score) o.readout_r2 = score->r2;
    }
  }
}

/// A simulated session: each object moved over the grid (and, with `outcome`, rolled out from
/// every place), and the objects read out of the features on other test scenes.
void MoveObjects(const store::Session& session, const SessionProbeOptions& options,
                 const std::vector<probe::ProbeSubject>& subjects, store::ProbeSummary& summary,
                 const SessionProbeProgress& progress, const std::atomic<bool>* cancel) {
  const auto report = [&progress](const char* what) -> probe::ProbeProgress {
    return [&progress, what](int done, int total) {
      if (progress) progress(what, done, total);
    };
  };
  const std::unique_ptr<worlds::World> world = MakeSessionWorld(session.manifest(), "none");
  const uint64_t test_seed = DefaultTestSeed(session);
  summary.scene_seed = Rng::Derive(test_seed, 0);  // the first rollout's scene
  const probe::ProbeResult result =
      probe::ProbeObjects(*world, summary.scene_seed, options.objects, options.grid, subjects,
                          report("moving objects"), cancel);
  std::optional<probe::OutcomeResult> outcomes;
  if (options.outcome) {
    outcomes = probe::ProbeOutcomes(*world, summary.scene_seed, options.objects, options.grid,
                                    subjects, report("rolling out from each place"), cancel);
  }
  world->Reset(summary.scene_seed);
  summary.layout = world->ObjectLayout();
  summary.readout_seed = Rng::Derive(test_seed, kReadoutStream);
  summary.readout_scenes = options.readout_scenes;
  std::vector<uint64_t> seeds;
  for (int i = 0; i < options.readout_scenes; ++i) {
    seeds.push_back(Rng::Derive(summary.readout_seed, static_cast<uint64_t>(i)));
  }
  const probe::SceneFrames frames =
      probe::RenderScenes(*world, seeds, report("rendering read-out scenes"), cancel);
  const probe::ObjectProbe& any = result.probes.front().front();
  summary.nx = any.nx;
  summary.ny = any.ny;
  summary.bounds = any.bounds;
  for (size_t m = 0; m < subjects.size(); ++m) {
    const auto scores = probe::ReadOutObjects(subjects[m], frames);
    store::ProbedMethod& probed = summary.methods[subjects[m].method];
    for (size_t k = 0; k < result.probes[m].size(); ++k) {
      const probe::ObjectProbe& p = result.probes[m][k];
      store::ProbedObject& o = probed.objects[p.object];
      o.action_change_per_10cm = p.action_change_per_10cm;
      o.feature_change_per_10cm = p.feature_change_per_10cm;
      o.action_change = p.action_change;
      const auto score = scores.find(p.object);
      if (score != scores.end() && score->second) o.readout_r2 = score->second->r2;
      if (outcomes) {
        const probe::ObjectOutcome& rolled = outcomes->outcomes[m][k];
        o.outcome = rolled.succeeded;
        o.success_rate = rolled.success_rate;
        o.home_succeeded = rolled.home_succeeded;
      }
    }
  }
}

}  // namespace

std::vector<std::string> TrainedMethods(const store::Session& session,
                                        const std::vector<std::string>& asked,
                                        const std::string& purpose) {
  std::vector<std::string> methods = asked;
  if (methods.empty()) {
    for (const char* method : {"baseline", "recon"}) {
      if (fs::exists(session.CheckpointPath(method))) {
        methods.push_back(method);
      } else if (fs::exists(session.TrainingRecordPath(method))) {
        // Trained once, its model gone since: left out, but not without a word.
        std::fprintf(stderr,
                     "recon: note: %s was trained (%s) but its model %s is gone: it is left "
                     "out; retrain it with `recon train --session %s --methods %s`\n",
                     method, store::Session::TrainingRecordRelativePath(method).c_str(),
                     store::Session::CheckpointRelativePath(method).c_str(), session.dir().c_str(),
                     method);
      }
    }
    if (methods.empty()) {
      throw UserError("session " + session.dir() + " has no trained method " + purpose +
                      ": run `recon train --session " + session.dir() +
                      "` first; nothing was written");
    }
  }
  for (const std::string& method : methods) {
    learn::ParseMethod(method);
    if (!fs::exists(session.CheckpointPath(method))) {
      throw UserError(method + " is not trained: there is no " + session.CheckpointPath(method) +
                      " (run `recon train --session " + session.dir() + " --methods " + method +
                      "`); nothing was written");
    }
  }
  return methods;
}

std::string MethodLabel(const store::Session& session, const std::string& method) {
  const std::optional<store::TrainingRecord> trained = store::ReadTrainingRecord(session, method);
  return trained ? trained->label : method;
}

store::ProbeSummary ProbeSession(const store::Session& session, const SessionProbeOptions& options,
                                 const SessionProbeProgress& progress,
                                 const std::atomic<bool>* cancel) {
  const auto started = std::chrono::steady_clock::now();
  const store::SessionManifest& manifest = session.manifest();
  const bool simulated = manifest.cell == "simulated";
  if (!simulated && (!options.objects.empty() || options.outcome)) {
    throw UserError(
        "moving objects (" + std::string(options.outcome ? "whole rollouts" : "--object") +
        ") needs the simulated cell, and " + session.dir() + " was taught on a " + manifest.cell +
        " cell; without them its recorded frames are read out; nothing was written");
  }
  if (simulated &&
      (options.readout_scenes < kMinReadoutScenes || options.readout_scenes > kMaxReadoutScenes)) {
    throw UserError("the read-out needs " + std::to_string(kMinReadoutScenes) + " to " +
                    std::to_string(kMaxReadoutScenes) + " test scenes, got " +
                    std::to_string(options.readout_scenes));
  }
  const std::vector<std::string> methods = TrainedMethods(session, options.methods, "to probe");
  store::ProbeSummary summary;
  const std::vector<probe::ProbeSubject> subjects = LoadSubjects(session, methods, summary);
  if (!simulated) {
    if (progress) progress("reading out recorded frames", 0, 1);
    ReadOutRecordedFrames(session, subjects, summary);
    if (progress) progress("reading out recorded frames", 1, 1);
  } else {
    MoveObjects(session, options, subjects, summary, progress, cancel);
  }
  if (cancel != nullptr && cancel->load()) throw probe::ProbeCancelled{};
  WriteHeatMaps(session, summary);
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  store::WriteProbeSummary(session.ProbeSummaryPath(), summary);
  return summary;
}

std::string ProbeStaleness(const store::Session& session, const store::ProbeSummary& summary) {
  std::string retrained;
  for (const auto& [method, probed] : summary.methods) {
    if (probed.model_id && CheckpointModelId(session.CheckpointPath(method)) != *probed.model_id) {
      retrained += (retrained.empty() ? "" : ", ") + probed.label;
    }
  }
  return retrained.empty() ? ""
                           : retrained + " retrained (or removed) since it was probed: probe again";
}

}  // namespace recon::cli
