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

}  // namespace

json ProbeSummaryToJson(const ProbeSummary& summary) {
  json methods = json::object(), labels = json::object(), model_ids = json::object();
  for (const auto& [method, probed] : summary.methods) {
    json objects = json::object();
    for (const auto& [object, o] : probed.objects) {
      objects[object] = {{"action_change_per_10cm", o.action_change_per_10cm},
                         {"feature_change_per_10cm", o.feature_change_per_10cm},
                         {"readout_r2", OptionalNumber(o.readout_r2)},
                         {"figure", OptionalText(o.figure)},
                         {"action_change", o.action_change}};
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
          {"readout", {{"scenes", summary.readout_scenes}, {"seed", summary.readout_seed}}},
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
      o.action_change_per_10cm = fields.Number("action_change_per_10cm");
      o.feature_change_per_10cm = fields.Number("feature_change_per_10cm");
      const double r2 = fields.OptionalNumberOrNan("readout_r2", NAN);
      if (std::isfinite(r2)) o.readout_r2 = r2;
      o.figure = fields.OptionalNullableString("figure");
      o.action_change = fields.OptionalNumbers("action_change");
      if (!o.action_change.empty() &&
          o.action_change.size() != static_cast<size_t>(summary.nx) * summary.ny) {
        fields.Fail("action_change", "expected " + std::to_string(summary.nx * summary.ny) +
                                         " values (the grid's cells)");
      }
      if (o.figure) {
        const std::filesystem::path p(*o.figure);
        if (p.is_absolute() || p.lexically_normal().string().rfind("..", 0) == 0) {
          fields.Fail("figure", "\"" + *o.figure + "\" is outside the session");
        }
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
