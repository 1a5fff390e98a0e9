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
#include "engine/learn/learner.h"
#include "engine/probe/feature_readout.h"
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

probe::ProbeSubject Subject(const std::string& method, const std::string& label,
                            const learn::Policy& policy) {
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
  return subject;
}

/// One heat map per method and object into the session, each object's maps on one scale.
void WriteHeatMaps(const store::Session& session, store::ProbeSummary& summary) {
  EnsureWritableDirectory(fs::path(session.ProbeSummaryPath()).parent_path().string());
  for (auto& [method, probed] : summary.methods) {
    for (auto& [object, o] : probed.objects) {
      // Wide, as the table is from behind the robot (1 m across, 0.6 m deep).
      report::WriteChart(ProbeHeatMap(summary, method, object),
                         session.ProbeFigurePath(method, object), 720, 470);
      o.figure = store::Session::ProbeFigureRelativePath(method, object);
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
      if (fs::exists(session.CheckpointPath(method))) methods.push_back(method);
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

std::string ProbeNote(const store::ProbeSummary& summary) {
  char note[256];
  std::snprintf(note, sizeof(note),
                "Objects moved one at a time over a %d x %d grid in test scene %llu; read-out "
                "fitted and scored on %d other test scenes (seeds from %llu, one in four held "
                "out).",
                summary.nx, summary.ny, static_cast<unsigned long long>(summary.scene_seed),
                summary.readout_scenes, static_cast<unsigned long long>(summary.readout_seed));
  return note;
}

report::HeatMap ProbeHeatMap(const store::ProbeSummary& summary, const std::string& method,
                             const std::string& object) {
  const store::ProbedMethod& probed = summary.methods.at(method);
  const store::ProbedObject& o = probed.objects.at(object);
  double top = 0;  // the object's largest change over every method: one colour scale
  for (const auto& [other, p] : summary.methods) {
    const auto found = p.objects.find(object);
    if (found == p.objects.end()) continue;
    for (double v : found->second.action_change) {
      if (std::isfinite(v)) top = std::max(top, v);
    }
  }
  report::HeatMap map;
  map.title = probed.label + ": the " + object + " moved";
  char subtitle[160];
  std::snprintf(subtitle, sizeof(subtitle),
                "action change %.3g per 10 cm of %s motion; scene seed %llu, everything else held",
                o.action_change_per_10cm, object.c_str(),
                static_cast<unsigned long long>(summary.scene_seed));
  map.subtitle = subtitle;
  map.value_label = "action change";
  map.x_min = summary.bounds[0];
  map.x_max = summary.bounds[1];
  map.y_min = summary.bounds[2];
  map.y_max = summary.bounds[3];
  map.nx = summary.nx;
  map.ny = summary.ny;
  map.values = o.action_change;
  map.scale_max = top;
  map.robot_view = true;
  for (const auto& [name, xy] : summary.layout) {
    map.markers.push_back({xy[0], xy[1], name == object ? name + " (home)" : name});
  }
  return map;
}

store::ProbeSummary ProbeSession(const store::Session& session, const SessionProbeOptions& options,
                                 const SessionProbeProgress& progress,
                                 const std::atomic<bool>* cancel) {
  const auto started = std::chrono::steady_clock::now();
  const store::SessionManifest& manifest = session.manifest();
  if (manifest.cell != "simulated") {
    throw UserError("the probe moves objects in the simulated cell, and " + session.dir() +
                    " was taught in a " + manifest.cell +
                    " cell, which RECON Studio cannot simulate; nothing was written");
  }
  if (options.readout_scenes < kMinReadoutScenes || options.readout_scenes > kMaxReadoutScenes) {
    throw UserError("the read-out needs " + std::to_string(kMinReadoutScenes) + " to " +
                    std::to_string(kMaxReadoutScenes) + " test scenes, got " +
                    std::to_string(options.readout_scenes));
  }
  const std::vector<std::string> methods = TrainedMethods(session, options.methods, "to probe");
  std::vector<probe::ProbeSubject> subjects;
  store::ProbeSummary summary;
  for (const std::string& method : methods) {
    const std::string label = MethodLabel(session, method);
    subjects.push_back(Subject(method, label, learn::LoadPolicy(session.CheckpointPath(method))));
    store::ProbedMethod& probed = summary.methods[method];
    probed.label = label;
    const std::string model_id = CheckpointModelId(session.CheckpointPath(method));
    if (!model_id.empty()) probed.model_id = model_id;
  }
  const std::unique_ptr<worlds::World> world = MakeSessionWorld(manifest, "none");
  const uint64_t test_seed = DefaultTestSeed(session);
  summary.scene_seed = Rng::Derive(test_seed, 0);  // the first rollout's scene
  const probe::ProbeResult result = probe::ProbeObjects(
      *world, summary.scene_seed, options.objects, options.grid, subjects,
      [&](int done, int total) {
        if (progress) progress("moving objects", done, total);
      },
      cancel);
  world->Reset(summary.scene_seed);
  summary.layout = world->ObjectLayout();

  summary.readout_seed = Rng::Derive(test_seed, kReadoutStream);
  summary.readout_scenes = options.readout_scenes;
  std::vector<uint64_t> seeds;
  for (int i = 0; i < options.readout_scenes; ++i) {
    seeds.push_back(Rng::Derive(summary.readout_seed, static_cast<uint64_t>(i)));
  }
  const probe::SceneFrames frames = probe::RenderScenes(
      *world, seeds,
      [&](int done, int total) {
        if (progress) progress("rendering read-out scenes", done, total);
      },
      cancel);
  const probe::ObjectProbe& any = result.probes.front().front();
  summary.nx = any.nx;
  summary.ny = any.ny;
  summary.bounds = any.bounds;
  for (size_t m = 0; m < subjects.size(); ++m) {
    const auto scores = probe::ReadOutObjects(subjects[m], frames);
    store::ProbedMethod& probed = summary.methods[methods[m]];
    for (const probe::ObjectProbe& p : result.probes[m]) {
      store::ProbedObject& o = probed.objects[p.object];
      o.action_change_per_10cm = p.action_change_per_10cm;
      o.feature_change_per_10cm = p.feature_change_per_10cm;
      o.action_change = p.action_change;
      const auto score = scores.find(p.object);
      if (score != scores.end() && score->second) o.readout_r2 = score->second->r2;
    }
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

std::vector<std::string> ProbeVerdicts(const store::ProbeSummary& summary) {
  std::vector<std::string> verdicts;
  for (const auto& [method, probed] : summary.methods) {
    const std::pair<const std::string, store::ProbedObject>* most = nullptr;
    for (const auto& entry : probed.objects) {
      if (most == nullptr ||
          entry.second.action_change_per_10cm > most->second.action_change_per_10cm) {
        most = &entry;
      }
    }
    if (most == nullptr) continue;
    char line[256];
    std::snprintf(line, sizeof(line), "%s moves most with the %s (%.3g per 10 cm",
                  probed.label.c_str(), most->first.c_str(), most->second.action_change_per_10cm);
    std::string verdict = line;
    for (const auto& [object, o] : probed.objects) {
      if (object == most->first) continue;
      std::snprintf(line, sizeof(line), "; the %s %.3g", object.c_str(), o.action_change_per_10cm);
      verdict += line;
    }
    verdicts.push_back(verdict + ")");
  }
  return verdicts;
}

std::string ProbeSummaryText(const store::ProbeSummary& summary) {
  std::string text;
  char line[256];
  std::snprintf(line, sizeof(line), "%-18s %-8s %16s %16s %10s\n", "method", "object",
                "action /10 cm", "feature /10 cm", "read-out R2");
  text += line;
  for (const auto& [method, probed] : summary.methods) {
    for (const auto& [object, o] : probed.objects) {
      char r2[32] = "-";
      if (o.readout_r2) std::snprintf(r2, sizeof(r2), "%.2f", *o.readout_r2);
      std::snprintf(line, sizeof(line), "%-18s %-8s %16.4g %16.4g %10s\n", probed.label.c_str(),
                    object.c_str(), o.action_change_per_10cm, o.feature_change_per_10cm, r2);
      text += line;
    }
  }
  text += ProbeNote(summary) + "\n";
  return text;
}

}  // namespace recon::cli
