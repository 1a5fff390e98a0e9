#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/core/beacon_spec.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/world.h"

namespace recon::worlds {

/// What the simulated cell's worlds need beyond a placement: a way to render camera images (the
/// application wires devices/render in; the engine never makes a GL context) and the image size.
struct CellResources {
  SceneRendererFactory renderer_factory;  ///< needed by worlds that observe camera images
  int image_size = 64;                    ///< camera images are image_size x image_size
  /// The tabletop's scene layout: "paper" (the plate at one of two places, demonstrations two per
  /// configuration) or "wide" (TabletopOptions::layout).
  std::string layout = "paper";
};

/// Layouts a world offers ({"paper", "wide"} for tabletop, empty for the others).
std::vector<std::string> WorldLayouts(const std::string& world);

/// The layout a new session or experiment of `world` uses when `asked` (empty: the world's
/// first, or "" for a world without layouts). UserError naming `option` for a layout the world
/// does not offer, or any layout for a world without them.
std::string ChooseLayout(const std::string& world, const std::string& asked,
                         const std::string& option);

/// The beacon noise a new session or experiment of `world` records with unless told otherwise:
/// a real DWM1001's for the tabletop (the paper's real beacon), 0 for the others.
double DefaultBeaconNoise(const std::string& world);

/// The noise injected into executed actions while demonstrating (worlds::DemoNoise) that a new
/// session or experiment of `world` uses unless told otherwise: 0 (off) in every world;
/// `--demo-noise` turns it on (docs/results.md measures both).
double DefaultDemoNoise(const std::string& world);

/// Names MakeWorld accepts: "dynamic2d" (image observations), "dynamic2d-state" (the 14-vector
/// state instead of the image), "static2d", and the simulated cell's "bintransfer" and
/// "tabletop" (camera images; needs CellResources::renderer_factory), and "tabletop-state" (the
/// tabletop with the objects' true positions instead of the image: a privileged diagnostic).
const std::vector<std::string>& WorldNames();

/// True for worlds that observe camera images of the MuJoCo cell and so need a renderer.
bool WorldNeedsRenderer(const std::string& name);

/// Valid beacon placements of a world (throws UserError naming the valid worlds for an unknown
/// name).
const std::vector<std::string>& WorldPlacements(const std::string& name);

/// The beacons a placement puts in a world, in the order their readings are concatenated in b
/// (empty for "none"). Sessions store each under its own name. Throws UserError for an unknown
/// world or placement.
std::vector<BeaconSpec> BeaconLayout(const std::string& world, const std::string& placement);

/// Builds a world by name with a beacon placement and noise. `authors_compat` reproduces the
/// authors' slips in Dynamic 2D and is ignored by the others (which have no reference code).
/// Throws UserError naming the valid worlds (or placements) when a name is unknown, and when a
/// world needs a renderer that `cell` does not provide.
std::unique_ptr<World> MakeWorld(const std::string& name, const std::string& placement,
                                 double noise_sigma, bool authors_compat,
                                 const CellResources& cell = {});

}  // namespace recon::worlds
