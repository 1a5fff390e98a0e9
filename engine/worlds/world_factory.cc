#include "engine/worlds/world_factory.h"

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/dynamic2d.h"
#include "engine/worlds/static2d.h"

namespace recon::worlds {
namespace {

[[noreturn]] void ThrowUnknownWorld(const std::string& name) {
  throw UserError("unknown world '" + name + "'; valid worlds: " + JoinNames(WorldNames()));
}

}  // namespace

const std::vector<std::string>& WorldNames() {
  static const std::vector<std::string> kNames = {"dynamic2d", "dynamic2d-state", "static2d"};
  return kNames;
}

const std::vector<std::string>& WorldPlacements(const std::string& name) {
  if (name == "dynamic2d" || name == "dynamic2d-state") return Dynamic2D::Placements();
  if (name == "static2d") return Static2D::Placements();
  ThrowUnknownWorld(name);
}

std::unique_ptr<World> MakeWorld(const std::string& name, const std::string& placement,
                                 double noise_sigma, bool authors_compat) {
  if (name == "dynamic2d" || name == "dynamic2d-state") {
    Dynamic2DOptions options;
    options.placement = placement;
    options.noise_sigma = noise_sigma;
    options.authors_compat = authors_compat;
    options.observation = name == "dynamic2d" ? "image" : "state";
    return MakeDynamic2D(options);
  }
  if (name == "static2d") {
    Static2DOptions options;
    options.placement = placement;
    options.noise_sigma = noise_sigma;
    return MakeStatic2D(options);
  }
  ThrowUnknownWorld(name);
}

}  // namespace recon::worlds
