#pragma once

// `recon eval --probe` (and the studio's "Check what it looks at"): the distractor probe and the
// feature read-out of a session's trained methods, with their heat maps, kept in the session.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "engine/probe/distractor_probe.h"
#include "engine/report/heat_map.h"
#include "engine/store/probe_summary.h"
#include "engine/store/session.h"

namespace recon::cli {

struct SessionProbeOptions {
  std::vector<std::string> methods;  ///< empty: every trained method
  std::vector<std::string> objects;  ///< empty: every object of the world
  probe::ProbeGrid grid;             ///< 10 x 10 over the whole table by default
  int readout_scenes = 60;           ///< test scenes the read-out is fitted and scored on
  /// Also a whole rollout from each place (slower by the episode's length): does the policy
  /// still do the task with the object there?
  bool outcome = false;
};

/// How far the probe has come: a short phrase and units done of all.
using SessionProbeProgress = std::function<void(const std::string& what, int done, int total)>;

/// Probes every method on the first scene of the session's test plan (the first rollout's),
/// reads the objects out of its features on `readout_scenes` other test scenes, writes the heat
/// maps and probe/probe.json into the session, and returns the summary. A real cell's session
/// cannot be simulated: its methods are read out on its recorded frames against the beacons'
/// readings instead, and nothing is moved. Everything it needs is checked before it writes:
/// UserError for a method that is not trained, an object the world does not have (naming the
/// valid ones), a grid that leaves the table, or objects or outcomes asked of a real cell's
/// session. probe::ProbeCancelled when cancelled.
store::ProbeSummary ProbeSession(const store::Session& session, const SessionProbeOptions& options,
                                 const SessionProbeProgress& progress = nullptr,
                                 const std::atomic<bool>* cancel = nullptr);

/// The heat map of `method` moving `object` (both in `summary`): the action change per grid
/// cell, seen from behind the robot, on the object's colour scale shared by every method.
report::HeatMap ProbeHeatMap(const store::ProbeSummary& summary, const std::string& method,
                             const std::string& object);

/// The methods `asked` (every trained one when empty), each checked to be trained first:
/// UserError naming what is missing (and that nothing was written), e.g. "session S has no
/// trained method to probe" for `purpose` "to probe".
std::vector<std::string> TrainedMethods(const store::Session& session,
                                        const std::vector<std::string>& asked,
                                        const std::string& purpose);
/// The method's label as its training record has it ("RECON (Play)"); the method without one.
std::string MethodLabel(const store::Session& session, const std::string& method);

/// The map of where `method`'s whole rollouts succeeded with `object` moved (1) or failed (0).
report::HeatMap ProbeOutcomeMap(const store::ProbeSummary& summary, const std::string& method,
                                const std::string& object);
/// Whether the probe rolled out from its places (SessionProbeOptions::outcome).
bool HasOutcomes(const store::ProbeSummary& summary);

/// How the probe was made, in one sentence: the grid, the scene and the read-out's scenes (or
/// recorded frames).
std::string ProbeNote(const store::ProbeSummary& summary);

/// Why the probe no longer describes the session's models ("RECON (Play) retrained (or removed)
/// since it was probed: probe again"); "" when it does.
std::string ProbeStaleness(const store::Session& session, const store::ProbeSummary& summary);

/// Per method, the object its action moves with most: "RECON (Play) moves most with the plate
/// (0.00216 per 10 cm; the bowl 0.000318)"; where it was rolled out from, "RECON (Play)
/// succeeds from 95 % of the bowl's places, ..."; and what its features encode: "RECON (Play)'s
/// features encode the plate (R² 0.97), not the bowl (R² 0.08)" (R² 0.5 or more encodes).
std::vector<std::string> ProbeVerdicts(const store::ProbeSummary& summary);

/// The summary as a table for people, one row per method and object, then the verdicts.
std::string ProbeSummaryText(const store::ProbeSummary& summary);

}  // namespace recon::cli
