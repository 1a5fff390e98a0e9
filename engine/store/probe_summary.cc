#include "engine/store/probe_summary.h"

#include <cmath>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/store/json_fields.h"

namespace recon::store {

using json = nlohmann::json;

namespace {

json OptionalNumber(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? json(*v) : json(nullptr);
}

json OptionalText(const std::optional<std::string>& v) { return v ? json(*v) : json(nullptr); }

/// A number, or none for null or a missing key (a probe that did not measure it).
std::optional<double> NullableNumber(const FieldReader& fields, const std::string& key) {
  const double v = fields.OptionalNumberOrNan(key, NAN);
  return std::isfinite(v) ? std::make_optional(v) : std::nullopt;
}

/// A figure's path, refused when it leads out of the session.
std::optional<std::string> SessionFigure(const FieldReader& fields, const std::string& key) {
  std::optional<std::string> figure = fields.OptionalNullableString(key);
  if (figure) {
    const std::filesystem::path p(*figure);
    if (p.is_absolute() || p.lexically_normal().string().rfind("..", 0) == 0) {
      fields.Fail(key, "\"" + *figure + "\" is outside the session");
    }
  }
  return figure;
}

/// One value per grid cell, or none.
std::vector<double> GridValues(const FieldReader& fields, const std::string& key,
                               const ProbeSummary& summary) {
  std::vector<double> values = fields.OptionalNumbers(key);
  if (!values.empty() && values.size() != static_cast<size_t>(summary.nx) * summary.ny) {
    fields.Fail(
        key, "expected " + std::to_string(summary.nx * summary.ny) + " values (the grid's cells)");
  }
  return values;
}

}  // namespace

json ProbeSummaryToJson(const ProbeSummary& summary) {
  json methods = json::object(), labels = json::object(), model_ids = json::object();
  for (const auto& [method, probed] : summary.methods) {
    json objects = json::object();
    for (const auto& [object, o] : probed.objects) {
      objects[object] = {{"action_change_per_10cm", OptionalNumber(o.action_change_per_10cm)},
                         {"feature_change_per_10cm", OptionalNumber(o.feature_change_per_10cm)},
                         {"readout_r2", OptionalNumber(o.readout_r2)},
                         {"figure", OptionalText(o.figure)},
                         {"action_change", o.action_change},
                         {"success_rate", OptionalNumber(o.success_rate)},
                         {"outcome", o.outcome},
                         {"home_succeeded", o.home_succeeded ? json(*o.home_succeeded) : json()},
                         {"outcome_figure", OptionalText(o.outcome_figure)}};
    }
    methods[method] = objects;
    labels[method] = probed.label;
    model_ids[method] = OptionalText(probed.model_id);
  }
  json layout = json::object();
  for (const auto& [object, xy] : summary.layout) layout[object] = {xy[0], xy[1]};
  return {{"methods", methods},
          {"layout", layout},
          {"labels", labels},
          {"model_ids", model_ids},
          {"scene_seed", summary.scene_seed},
          {"grid",
           {{"nx", summary.nx},
            {"ny", summary.ny},
            {"bounds_m",
             {summary.bounds[0], summary.bounds[1], summary.bounds[2], summary.bounds[3]}}}},
          {"readout",
           {{"scenes", summary.readout_scenes},
            {"seed", summary.readout_seed},
            {"recorded_frames", summary.readout_frames},
            {"recorded_episodes", summary.readout_episodes}}},
          {"seconds", summary.seconds}};
}

ProbeSummary ProbeSummaryFromJson(const json& value, const std::string& source) {
  const FieldReader top(value, source, "");
  ProbeSummary summary;
  summary.scene_seed = top.OptionalUnsigned("scene_seed", 0);
  summary.seconds = top.OptionalNumberOrNan("seconds", 0.0);
  if (top.Has("grid")) {
    const FieldReader grid = top.Object("grid");
    summary.nx = static_cast<int>(grid.OptionalInteger("nx", 0));
    summary.ny = static_cast<int>(grid.OptionalInteger("ny", 0));
    const std::vector<double> bounds = grid.OptionalNumbers("bounds_m");
    if (!bounds.empty() && bounds.size() != 4) {
      grid.Fail("bounds_m", "expected [x_min, x_max, y_min, y_max]");
    }
    for (size_t i = 0; i < bounds.size(); ++i) summary.bounds[i] = bounds[i];
  }
  if (top.Has("readout")) {
    const FieldReader readout = top.Object("readout");
    summary.readout_scenes = static_cast<int>(readout.OptionalInteger("scenes", 0));
    summary.readout_seed = readout.OptionalUnsigned("seed", 0);
    summary.readout_frames = static_cast<int>(readout.OptionalInteger("recorded_frames", 0));
    summary.readout_episodes = static_cast<int>(readout.OptionalInteger("recorded_episodes", 0));
  }
  if (top.Has("layout")) {
    const FieldReader layout = top.Object("layout");
    for (const auto& [object, xy] : layout.object().items()) {
      if (!xy.is_array() || xy.size() != 2 || !xy[0].is_number() || !xy[1].is_number()) {
        layout.Fail(object, "expected [x, y] in metres");
      }
      summary.layout[object] = {xy[0].get<double>(), xy[1].get<double>()};
    }
  }
  const FieldReader labels = top.Has("labels") ? top.Object("labels") : top;
  const FieldReader model_ids = top.Has("model_ids") ? top.Object("model_ids") : top;
  const FieldReader methods = top.Object("methods");
  for (const auto& [method, objects_value] : methods.object().items()) {
    const FieldReader objects = methods.Object(method);
    ProbedMethod probed;
    probed.label = top.Has("labels") ? labels.OptionalString(method, method) : method;
    if (top.Has("model_ids")) probed.model_id = model_ids.OptionalNullableString(method);
    for (const auto& [object, fields_value] : objects.object().items()) {
      const FieldReader fields = objects.Object(object);
      ProbedObject o;
      o.action_change_per_10cm = NullableNumber(fields, "action_change_per_10cm");
      o.feature_change_per_10cm = NullableNumber(fields, "feature_change_per_10cm");
      o.readout_r2 = NullableNumber(fields, "readout_r2");
      o.success_rate = NullableNumber(fields, "success_rate");
      o.figure = SessionFigure(fields, "figure");
      o.outcome_figure = SessionFigure(fields, "outcome_figure");
      o.action_change = GridValues(fields, "action_change", summary);
      o.outcome = GridValues(fields, "outcome", summary);
      if (fields.Has("home_succeeded") && !fields.object().at("home_succeeded").is_null()) {
        o.home_succeeded = fields.Boolean("home_succeeded", false);
      }
      probed.objects[object] = o;
    }
    summary.methods[method] = probed;
  }
  return summary;
}

void WriteProbeSummary(const std::string& path, const ProbeSummary& summary) {
  WriteFileAtomically(path, ProbeSummaryToJson(summary).dump(2) + "\n");
}

std::optional<ProbeSummary> ReadProbeSummary(const Session& session) {
  const std::string path = session.ProbeSummaryPath();
  const std::optional<json> value = ReadJsonFile(path);
  if (!value) return std::nullopt;
  return ProbeSummaryFromJson(*value, path);
}

}  // namespace recon::store
