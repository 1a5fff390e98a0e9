#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "app/cli/result_staleness.h"
#include "engine/store/session.h"

namespace recon::cli {

/// `recon session info --json`: {"episodes": committed usable demonstrations, "play": play
/// samples, ...} plus samples, splits, bad and damaged episodes, the teaching-time ledger, the
/// calibration, and what training and rollouts have produced (`results`, as their files hold
/// them, each with "out_of_date").
nlohmann::json SessionInfoJson(const store::Session& session, const SessionResults& results);
/// The same for people.
std::string SessionInfoText(const store::Session& session, const nlohmann::json& info,
                            const SessionResults& results);
/// `recon session episodes --json`: one object per episode.
nlohmann::json EpisodesJson(const store::Session& session);
/// The teaching-time ledger: what the session's demonstrations, play and beacon placements cost,
/// and what the Baseline (no beacons, no play) and RECON would each have cost the teacher.
nlohmann::json TeachingLedgerJson(const store::Session& session);

}  // namespace recon::cli
