#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/report/heat_map.h"

namespace recon::report {

/// Everything the session report shows, as plain data: the caller (the CLI) reads the session,
/// the training logs and the evaluation results and fills this in; the report only lays it out.
/// Any part may be empty: its section then says what is missing and which command fills it.
struct SessionReport {
  std::string title;         ///< e.g. "Teaching session: tabletop"
  std::string session_path;  ///< shown in the header
  std::string generated;     ///< e.g. "2024-05-01 14:03 UTC"; shown under the title when set
  /// Overview table rows: world, created, episodes, play samples, seeds, devices, beacons...
  std::vector<std::pair<std::string, std::string>> facts;

  /// The loss history of one training run (e.g. "RECON", "Baseline").
  struct LossHistory {
    std::string label;
    /// One entry per logged step; beacon/play may be empty (the Baseline has no such heads).
    std::vector<double> step, action_loss, beacon_loss, play_loss, total_loss;
    std::string note;  ///< e.g. "6001 steps, seed 7, 41 s"
    /// Why this run no longer matches the session's data (shown as a warning); empty if it does.
    std::string out_of_date;
  };
  std::vector<LossHistory> losses;

  /// One beacon's readings over one recorded episode.
  struct BeaconTrace {
    std::string episode;        ///< "demo_3"
    std::string beacon;         ///< "plate"
    std::string object;         ///< the object it marks
    std::string unit;           ///< "m"
    double step_seconds = 0.1;  ///< time axis = index * step_seconds (0 => use the step index)
    std::vector<std::string> component_names;  ///< "x", "y"
    std::vector<std::vector<double>> values;   ///< [component][time step]; NaN = no reading
  };
  std::vector<BeaconTrace> beacon_traces;

  /// The fit of the UWB frame to the table frame used while recording.
  struct Calibration {
    bool present = false;
    double rmse_m = 0, mean_m = 0, median_m = 0, p95_m = 0, threshold_m = 0.10;
    bool passed = false;
    std::vector<double> residual_m;  ///< one per calibration point
    std::vector<bool> inlier;        ///< same size (empty: every point is an inlier)
  };
  Calibration calibration;

  /// A trained policy rolled out with the beacons removed.
  struct Rollout {
    std::string label;        ///< "RECON", "Baseline"
    std::string metric_name;  ///< "final distance of the toast to the plate (m)"
    bool higher_is_better = false;
    double metric_mean = 0, metric_sem = 0;
    int tests = 0;
    bool has_success = false;
    double success_rate = 0, success_sem = 0;  ///< fractions in [0, 1]
    std::map<std::string, double> details;
    std::string note;  ///< e.g. "20 test scenarios, seeds ..."
    /// Why these rollouts no longer describe the method's model (a warning); empty if they do.
    std::string out_of_date;
  };
  std::vector<Rollout> rollouts;

  /// A method's trials on a real arm (a real cell's Rollouts step), judged by the person.
  struct RealTrials {
    std::string label;
    std::string cell;  ///< the cell and its devices (RealTrialLog::cell)
    struct Trial {
      int number = 0;
      bool succeeded = false, stopped = false;
      std::string reason;
      int steps = 0;
      double seconds = 0;
      /// How the method's simulated rollout of the same test scene went, where the session has
      /// one (a session taught in the simulated cell, tried on a real arm).
      std::optional<bool> simulated_succeeded;
    };
    std::vector<Trial> trials;
    int successes = 0;
    std::string out_of_date;  ///< why they are not of the method's current model; "" if they are
  };
  std::vector<RealTrials> real_trials;

  /// What the trained methods look at (`recon eval --probe`): each object moved over the table
  /// with everything else held, and read out of the features.
  struct Probe {
    struct Row {
      std::string label, object;
      /// None when the objects were not moved (a real cell's session, read out only).
      std::optional<double> action_change_per_10cm, feature_change_per_10cm;
      std::optional<double> readout_r2;    ///< none where the object never moved
      std::optional<double> success_rate;  ///< with whole rollouts from each place
    };
    std::vector<Row> rows;
    std::vector<std::string> verdicts;  ///< what each method moves with and encodes
    std::vector<HeatMap> maps;          ///< one per method and object, each object's on one scale
    std::vector<HeatMap> outcome_maps;  ///< where whole rollouts succeeded, when rolled out
    std::string note;                   ///< the scene, the grid and the read-out's scenes
    std::string out_of_date;  ///< why it is not of the methods' current models; "" if it is
  };
  std::optional<Probe> probe;

  /// Teaching time of one way of teaching the task, in seconds.
  struct LedgerRow {
    std::string label;  ///< "Baseline (4 demos)", "RECON (Play)"
    double demonstrations_s = 0, beacon_placements_s = 0, play_s = 0, total_s = 0;
    std::optional<double> paper_total_s;  ///< the paper's number for the same row, if any
  };
  std::vector<LedgerRow> ledger;
  std::string ledger_note;
};

/// Writes out_dir/report.html and every figure as out_dir/figures/*.png; creates out_dir. The
/// HTML is self-contained (figures embedded as data: URIs, inline CSS, no scripts or fonts), so
/// it can be mailed or archived alone. report.html is written last and atomically, so a failure
/// never leaves a half-written report; PNGs in figures/ from an earlier report that this one
/// does not contain are removed. Returns the paths written (figures first, report.html last).
/// Throws UserError naming the path if something cannot be written, or the field if the data
/// is inconsistent (e.g. a loss history whose columns differ in length).
std::vector<std::string> WriteSessionReport(const SessionReport& report,
                                            const std::string& out_dir);

}  // namespace recon::report
