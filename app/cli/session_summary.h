#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "engine/store/session.h"

namespace recon::cli {

/// `recon session info --json`: {"episodes": committed usable demonstrations, "play": play
/// samples, ...} plus samples, splits, bad and damaged episodes, the teaching-time ledger, the
/// calibration, and what training and rollouts have produced.
nlohmann::json SessionInfoJson(const store::Session& session);
/// The same for people.
std::string SessionInfoText(const store::Session& session, const nlohmann::json& info);
/// `recon session episodes --json`: one object per episode.
nlohmann::json EpisodesJson(const store::Session& session);
/// The teaching-time ledger: what the session's demonstrations, play and beacon placements cost,
/// and what the Baseline (no beacons, no play) and RECON would each have cost the teacher.
nlohmann::json TeachingLedgerJson(const store::Session& session);

/// Reads a JSON file the session's tools wrote (training/, rollouts/); nullopt if absent.
/// UserError naming the file if it is not valid JSON.
std::optional<nlohmann::json> ReadJsonFile(const std::string& path);

}  // namespace recon::cli
