#include "engine/experiments/condition.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace recon::experiments {

namespace {

struct KnownCondition {
  const char* name;
  const char* label;
  const char* placement;
  learn::Method method;
  bool use_play;
};

// Dynamic 2D: beacon placements of the paper's Figure 5 (plus Distance, which the authors'
// code also offers). No play data: the moving objects make demonstrations diverse enough.
constexpr KnownCondition kDynamic2D[] = {
    {"baseline", "Baseline", "none", learn::Method::kBaseline, false},
    {"exact", "Exact", "exact", learn::Method::kRecon, false},
    {"partial", "Partial", "partial", learn::Method::kRecon, false},
    {"other", "Other", "other", learn::Method::kRecon, false},
    {"random", "Random", "random", learn::Method::kRecon, false},
    {"exact+other", "Exact+Other", "exact+other", learn::Method::kRecon, false},
    {"exact+random", "Exact+Random", "exact+random", learn::Method::kRecon, false},
    {"distance", "Distance", "distance", learn::Method::kRecon, false},
};

// Static 2D: position (P) or distance (D) beacons, with and without play data (Figure 4, left).
constexpr KnownCondition kStatic2D[] = {
    {"baseline", "Baseline", "none", learn::Method::kBaseline, false},
    {"recon-p", "RECON-P", "position", learn::Method::kRecon, false},
    {"recon-d", "RECON-D", "distance", learn::Method::kRecon, false},
    {"recon-p-play", "RECON-P (Play)", "position", learn::Method::kRecon, true},
    {"recon-d-play", "RECON-D (Play)", "distance", learn::Method::kRecon, true},
};

// Bin transfer (the paper's Robosuite task): the same five conditions as Static 2D, with the
// right-most object's position (P) or the grip-to-object distance (D).
constexpr KnownCondition kBinTransfer[] = {
    {"baseline", "Baseline", "none", learn::Method::kBaseline, false},
    {"recon-p", "RECON-P", "position", learn::Method::kRecon, false},
    {"recon-d", "RECON-D", "distance", learn::Method::kRecon, false},
    {"recon-p-play", "RECON-P (Play)", "position", learn::Method::kRecon, true},
    {"recon-d-play", "RECON-D (Play)", "distance", learn::Method::kRecon, true},
};

// Tabletop (the paper's real-robot task): a beacon beside the plate, with or without the 4 s of
// play data in which the teacher moves the bowl around.
constexpr KnownCondition kTabletop[] = {
    {"baseline", "Baseline", "none", learn::Method::kBaseline, false},
    {"recon", "RECON", "plate", learn::Method::kRecon, false},
    {"recon-play", "RECON (Play)", "plate", learn::Method::kRecon, true},
};

std::vector<KnownCondition> Table(const std::string& world) {
  if (world == "dynamic2d") return {std::begin(kDynamic2D), std::end(kDynamic2D)};
  if (world == "static2d") return {std::begin(kStatic2D), std::end(kStatic2D)};
  if (world == "bintransfer") return {std::begin(kBinTransfer), std::end(kBinTransfer)};
  if (world == "tabletop" || world == "tabletop-state") {
    return {std::begin(kTabletop), std::end(kTabletop)};
  }
  throw UserError("unknown experiment world '" + world +
                  "' (valid: dynamic2d, static2d, bintransfer, tabletop)");
}

std::string FormatSigma(double sigma) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", sigma);
  return buf;
}

}  // namespace

std::vector<std::string> KnownConditionNames(const std::string& world) {
  std::vector<std::string> names;
  for (const KnownCondition& c : Table(world)) names.push_back(c.name);
  return names;
}

std::vector<std::string> DefaultConditionNames(const std::string& world) {
  if (world == "dynamic2d") {
    return {"baseline", "exact", "partial", "other", "random", "exact+other", "exact+random"};
  }
  if (world == "tabletop" || world == "tabletop-state") {
    return {"baseline", "recon-play"};  // the paper's comparison
  }
  return KnownConditionNames(world);
}

std::vector<Condition> ParseConditions(const std::string& world,
                                       const std::vector<std::string>& names,
                                       const std::vector<double>& exact_noise_levels) {
  const std::vector<KnownCondition> table = Table(world);
  std::vector<Condition> conditions;
  std::set<std::string> seen;
  auto add = [&](Condition c) {
    if (!seen.insert(c.name).second) {
      throw UserError("condition '" + c.name + "' is listed twice");
    }
    conditions.push_back(std::move(c));
  };
  for (const std::string& name : names) {
    const auto it = std::find_if(table.begin(), table.end(),
                                 [&](const KnownCondition& k) { return name == k.name; });
    if (it == table.end()) {
      throw UserError("unknown condition '" + name + "' for " + world +
                      " (valid: " + JoinNames(KnownConditionNames(world)) + ")");
    }
    add({it->name, it->label, it->placement, 0.0, it->method, it->use_play});
  }
  for (double sigma : exact_noise_levels) {
    if (!(sigma > 0.0)) {
      throw UserError("noise level " + FormatSigma(sigma) + " must be a positive sigma");
    }
    if (world != "dynamic2d") {
      throw UserError("--noise applies to dynamic2d's Exact placement only");
    }
    const std::string s = FormatSigma(sigma);
    add({"exact-sigma" + s, "Exact \xCF\x83=" + s, "exact", sigma, learn::Method::kRecon, false});
  }
  if (conditions.empty()) throw UserError("no conditions to run");
  return conditions;
}

}  // namespace recon::experiments
