#include "engine/experiments/sweep_plan.h"

#include <cmath>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>

#include "engine/core/digest.h"
#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::experiments {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

/// NaN and infinities as null (a diverged run's metric), read back as NaN.
json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double NumberOf(const json& v) { return v.is_null() ? std::nan("") : v.get<double>(); }

std::vector<double> NumbersOf(const json& v) {
  std::vector<double> out;
  for (const json& x : v) out.push_back(NumberOf(x));
  return out;
}

json LossesToJson(const learn::StepMetrics& m) {
  return {{"action", m.action_loss}, {"beacon", m.beacon_loss},
          {"play", m.play_loss},     {"consistency", m.consistency_loss},
          {"total", m.total_loss},   {"gate_mean", m.gate_mean},
          {"blind", m.blind_loss},   {"gate", m.gate_loss},
          {"attempt", m.attempt},    {"step", m.step}};
}

learn::StepMetrics LossesFromJson(const json& v) {
  learn::StepMetrics m;
  m.action_loss = static_cast<float>(NumberOf(v.at("action")));
  m.beacon_loss = static_cast<float>(NumberOf(v.at("beacon")));
  m.play_loss = static_cast<float>(NumberOf(v.at("play")));
  m.consistency_loss = static_cast<float>(NumberOf(v.at("consistency")));
  m.total_loss = static_cast<float>(NumberOf(v.at("total")));
  m.gate_mean = static_cast<float>(NumberOf(v.at("gate_mean")));
  m.blind_loss = static_cast<float>(NumberOf(v.at("blind")));
  m.gate_loss = static_cast<float>(NumberOf(v.at("gate")));
  m.attempt = v.at("attempt").get<int>();
  m.step = v.at("step").get<int>();
  return m;
}

json UnitToJson(const ExperimentUnit& u) {
  return {{"index", u.index}, {"demos", u.demos}, {"condition", u.condition}, {"run", u.run}};
}

ExperimentUnit UnitFromJson(const json& v) {
  return {v.at("index").get<int>(), v.at("demos").get<int>(), v.at("condition").get<size_t>(),
          v.at("run").get<int>()};
}

json DescribedToJson(const ExperimentResult& r) {
  return {{"metric_name", r.metric_name},
          {"higher_is_better", r.higher_is_better},
          {"expert_metric", Number(r.expert_metric)},
          {"metric_key", r.metric_key},
          {"has_success", r.has_success},
          {"step_seconds", r.step_seconds},
          {"episode_length", r.episode_length},
          {"play_per_scenario", r.play_per_scenario},
          {"expert_success_rate", Number(r.expert_success_rate)}};
}

ExperimentResult DescribedFromJson(const json& v) {
  ExperimentResult r;
  r.metric_name = v.at("metric_name").get<std::string>();
  r.higher_is_better = v.at("higher_is_better").get<bool>();
  r.expert_metric = NumberOf(v.at("expert_metric"));
  r.metric_key = v.at("metric_key").get<std::string>();
  r.has_success = v.at("has_success").get<bool>();
  r.step_seconds = v.at("step_seconds").get<double>();
  r.episode_length = v.at("episode_length").get<int>();
  r.play_per_scenario = v.at("play_per_scenario").get<int>();
  r.expert_success_rate = NumberOf(v.at("expert_success_rate"));
  return r;
}

/// Everything of the plan but its digest, in one canonical form (keys sorted).
json PlanBody(const SweepPlan& plan) {
  json units = json::array();
  for (size_t i = 0; i < plan.units.size(); ++i) {
    json unit = UnitToJson(plan.units[i]);
    unit["data_seed"] = plan.data_seeds.at(i);
    unit["train_seed"] = plan.train_seeds.at(i);
    units.push_back(unit);
  }
  return {{"version", plan.version},
          {"made_by", plan.made_by},
          {"arguments", plan.arguments},
          {"units", units},
          {"described", DescribedToJson(plan.described)}};
}

std::string Digest(const json& body) { return "fnv1a:" + DigestHex(Fnv1a(body.dump())); }

/// unit_K.timing.json beside unit_K.json.
std::string TimingPath(const std::string& unit_path) {
  return fs::path(unit_path).replace_extension(".timing.json").string();
}

std::string ReadText(const std::string& path) { return ReadWholeFile(path).value_or(""); }

}  // namespace

SweepPlan MakeSweepPlan(const ExperimentConfig& config, std::vector<std::string> arguments,
                        std::string made_by) {
  ValidateExperimentConfig(config);
  SweepPlan plan;
  plan.made_by = std::move(made_by);
  plan.arguments = std::move(arguments);
  plan.units = PlanUnits(config);
  for (const ExperimentUnit& unit : plan.units) {
    plan.data_seeds.push_back(DemoScenarioSeed(config.seed, unit.run, 0));
    plan.train_seeds.push_back(TrainSeed(config.seed, unit.run));
  }
  plan.described = DescribeExperiment(config);
  return plan;
}

std::string PlanPath(const std::string& dir) { return (fs::path(dir) / "plan.json").string(); }

std::string UnitPath(const std::string& dir, int index) {
  return (fs::path(dir) / "units" / ("unit_" + std::to_string(index) + ".json")).string();
}

void WriteSweepPlan(const std::string& dir, const SweepPlan& plan) {
  json value = PlanBody(plan);
  value["digest"] = Digest(value);
  EnsureWritableDirectory(dir);
  WriteFileAtomically(PlanPath(dir), value.dump(2) + "\n");
}

SweepPlan ReadSweepPlan(const std::string& dir) {
  const std::string path = PlanPath(dir);
  if (!fs::exists(path)) {
    throw UserError("no plan in " + dir + " (" + path + "): make one with `recon experiment " +
                    "<world> ... --plan-only --out " + dir + "`");
  }
  try {
    json value = json::parse(ReadText(path));
    const int version = value.at("version").get<int>();
    if (version != kSweepPlanVersion) {
      throw UserError(path + " is a plan of version " + std::to_string(version) +
                      "; this recon "
                      "reads version " +
                      std::to_string(kSweepPlanVersion) +
                      ": plan the sweep again with this binary");
    }
    const std::string digest = value.at("digest").get<std::string>();
    value.erase("digest");
    if (Digest(value) != digest) {
      throw UserError(path +
                      " was changed since it was written (its digest no longer matches): "
                      "plan the sweep again rather than editing the plan");
    }
    SweepPlan plan;
    plan.version = version;
    plan.made_by = value.at("made_by").get<std::string>();
    plan.arguments = value.at("arguments").get<std::vector<std::string>>();
    for (const json& unit : value.at("units")) {
      plan.units.push_back(UnitFromJson(unit));
      plan.data_seeds.push_back(unit.at("data_seed").get<uint64_t>());
      plan.train_seeds.push_back(unit.at("train_seed").get<uint64_t>());
    }
    plan.described = DescribedFromJson(value.at("described"));
    return plan;
  } catch (const json::exception& e) {
    throw UserError(path + " is not a readable plan: " + e.what());
  }
}

std::string UnitResultText(const UnitResult& result) {
  const RunResult& r = result.run;
  json run = {{"condition", r.condition},
              {"demos", r.demos},
              {"run", r.run},
              {"data_seed", r.data_seed},
              {"train_seed", r.train_seed},
              {"metric", Number(r.metric)},
              {"success_rate", Number(r.success_rate)},
              {"details", r.details},
              {"demo_samples", r.demo_samples},
              {"attempts", r.attempts},
              {"train_steps", r.train_steps},
              {"final_losses", LossesToJson(r.final_losses)}};
  json value = {{"version", kSweepPlanVersion}, {"unit", UnitToJson(result.unit)}, {"run", run}};
  if (result.curve) {
    value["curve"] = {{"condition", result.curve->condition},
                      {"demos", result.curve->demos},
                      {"step", result.curve->step},
                      {"action_loss", result.curve->action_loss}};
  }
  return value.dump(1) + "\n";
}

void WriteUnitResult(const std::string& dir, const SweepPlan& plan, const UnitResult& result,
                     double train_seconds, const std::string& host) {
  const std::string path = UnitPath(dir, result.unit.index);
  // A unit trains for minutes, and the plan it ran from may have been replaced meanwhile (a
  // plan nothing had run from yet is replaced without --force): its result must not be filed
  // as a unit of the new plan.
  const std::string unit = std::to_string(result.unit.index);
  const std::string not_written = "; the result of unit " + unit + " was not written: run it " +
                                  "again with `recon experiment run-unit " + dir + " --unit " +
                                  unit + "`";
  std::optional<SweepPlan> now;
  try {
    now = ReadSweepPlan(dir);
  } catch (const UserError& e) {
    throw UserError(std::string(e.what()) + not_written);
  }
  // The arguments give every unit and its seeds (ReadSweepPlan checked the rest by digest).
  if (now->arguments != plan.arguments || now->made_by != plan.made_by) {
    throw UserError(PlanPath(dir) + " was replaced by the plan of another sweep while unit " +
                    unit + " ran" + not_written);
  }
  EnsureWritableDirectory(fs::path(path).parent_path().string());
  WriteFileAtomically(path, UnitResultText(result));
  // The time goes beside it: a unit run twice writes the same result, not the same time.
  const json timing = {{"train_seconds", train_seconds}, {"host", host}};
  WriteFileAtomically(TimingPath(path), timing.dump() + "\n");
}

std::optional<UnitResult> ReadUnitResult(const std::string& dir, int index) {
  const std::string path = UnitPath(dir, index);
  if (!fs::exists(path)) return std::nullopt;
  try {
    const json value = json::parse(ReadText(path));
    if (value.at("version").get<int>() != kSweepPlanVersion) {
      throw UserError(path + " is a unit of another version");
    }
    UnitResult result;
    result.unit = UnitFromJson(value.at("unit"));
    if (result.unit.index != index) {
      throw UserError(path + " holds unit " + std::to_string(result.unit.index) + ", not " +
                      std::to_string(index));
    }
    const json& run = value.at("run");
    RunResult& r = result.run;
    r.condition = run.at("condition").get<std::string>();
    r.demos = run.at("demos").get<int>();
    r.run = run.at("run").get<int>();
    r.data_seed = run.at("data_seed").get<uint64_t>();
    r.train_seed = run.at("train_seed").get<uint64_t>();
    r.metric = NumberOf(run.at("metric"));
    r.success_rate = NumberOf(run.at("success_rate"));
    for (const auto& [key, v] : run.at("details").items()) r.details[key] = NumberOf(v);
    r.demo_samples = run.at("demo_samples").get<int64_t>();
    r.attempts = run.at("attempts").get<int>();
    r.train_steps = run.at("train_steps").get<int>();
    r.final_losses = LossesFromJson(run.at("final_losses"));
    if (value.contains("curve")) {
      const json& c = value.at("curve");
      LossCurve curve;
      curve.condition = c.at("condition").get<std::string>();
      curve.demos = c.at("demos").get<int>();
      curve.step = NumbersOf(c.at("step"));
      curve.action_loss = NumbersOf(c.at("action_loss"));
      result.curve = std::move(curve);
    }
    // The time, when it is there and whole (a unit copied without it still counts).
    try {
      const json timing = json::parse(ReadText(TimingPath(path)));
      r.train_seconds = timing.at("train_seconds").get<double>();
    } catch (const json::exception&) {
      r.train_seconds = 0;
    }
    return result;
  } catch (const json::exception& e) {
    throw UserError(path + " is damaged (" + e.what() + ")");
  }
}

}  // namespace recon::experiments
