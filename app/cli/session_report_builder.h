#pragma once

#include <string>

#include "engine/report/session_report.h"
#include "engine/store/session.h"

namespace recon::cli {

/// Gathers what a session's report shows: the overview, the training logs, one episode's beacon
/// traces (`episode`, or the first good demonstration when empty), the calibration, the rollouts
/// and the teaching-time ledger with the paper's numbers. Used by `recon report` and the studio.
report::SessionReport BuildSessionReport(const store::Session& session,
                                         const std::string& episode = "");

/// Builds and writes the report into `out_dir` (default: the session's report/ folder); returns
/// the path of report.html.
std::string WriteReportForSession(const store::Session& session, const std::string& out_dir = "",
                                  const std::string& episode = "");

}  // namespace recon::cli
