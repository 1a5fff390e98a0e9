#include "engine/teach/workflow.h"

#include <algorithm>
#include <cstdio>

namespace recon::teach {
namespace {

int Index(Step step) { return static_cast<int>(step); }

std::string Count(int n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string Join(const std::vector<std::string>& items) {
  std::string joined;
  for (const std::string& item : items) joined += (joined.empty() ? "" : ", ") + item;
  return joined;
}

bool Contains(const std::vector<std::string>& items, const std::string& item) {
  return std::find(items.begin(), items.end(), item) != items.end();
}

std::string Seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f s", s);
  return text;
}

std::string Meters(double m) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f m", m);
  return text;
}

std::string MethodTitle(const std::string& method) {
  if (method == kBaselineMethod) return "Baseline";
  if (method == kReconMethod) return "RECON";
  return method;
}

std::string Goto(const std::string& action, Step step) {
  return action + " (" + StepTitle(step) + ")";
}

/// Why a step waits on the earlier step `needed`: the earlier step's own reason when it is blocked
/// too, so the teacher is sent to where they can act; otherwise `action` to do there.
std::string Needs(const StepStatus& needed, const std::string& action) {
  if (needed.state == StepState::kBlocked) return needed.why_blocked;
  return Goto(action, needed.step);
}

StepStatus Blocked(Step step, std::string summary, std::string why) {
  return {step, StepState::kBlocked, std::move(summary), std::move(why)};
}

StepStatus ReadyOrDone(Step step, bool done, std::string summary) {
  return {step, done ? StepState::kDone : StepState::kReady, std::move(summary), ""};
}

bool NoBeacons(const WorkflowFacts& facts) { return facts.beacons_required <= 0; }
int MinDemos(const WorkflowFacts& facts) { return std::max(1, facts.min_demos); }

StepStatus EvaluateCell(const WorkflowFacts& facts) {
  std::string summary = facts.session_open ? "Session open" : "No session open";
  if (facts.cell_connected) {
    summary += "; all devices connected";
  } else if (facts.missing_devices.empty()) {
    summary += "; devices not connected";
  } else {
    summary += "; not connected: " + Join(facts.missing_devices);
  }
  return ReadyOrDone(Step::kCell, facts.session_open && facts.cell_connected, summary);
}

std::string CellAction(const WorkflowFacts& facts) {
  if (!facts.session_open) return "Open or create a session first";
  if (!facts.missing_devices.empty()) return "Connect " + Join(facts.missing_devices) + " first";
  return "Connect the cell first";
}

StepStatus EvaluateBeacons(const WorkflowFacts& facts, const StepStatus& cell) {
  const std::string summary = NoBeacons(facts)
                                  ? "No beacons in this task (Baseline only)"
                                  : std::to_string(facts.beacons_assigned) + " of " +
                                        Count(facts.beacons_required, "beacon") + " assigned";
  if (cell.state != StepState::kDone) {
    return Blocked(Step::kBeacons, summary, Needs(cell, CellAction(facts)));
  }
  return ReadyOrDone(Step::kBeacons,
                     NoBeacons(facts) || facts.beacons_assigned >= facts.beacons_required, summary);
}

std::string BeaconsAction(const WorkflowFacts& facts) {
  if (facts.unmarked_objects.size() == 1) {
    return "Assign a beacon to " + facts.unmarked_objects.front() + " first";
  }
  if (!facts.unmarked_objects.empty()) {
    return "Assign beacons to " + Join(facts.unmarked_objects) + " first";
  }
  return "Assign " +
         Count(std::max(1, facts.beacons_required - facts.beacons_assigned), "more beacon") +
         " first";
}

bool CalibrationFailed(const WorkflowFacts& facts) {
  return facts.calibration_present && !facts.calibration_passed;
}

StepStatus EvaluateCalibrate(const WorkflowFacts& facts, const StepStatus& beacons) {
  std::string summary;
  if (NoBeacons(facts)) {
    summary = "No beacons to calibrate";
  } else if (!facts.calibration_present) {
    summary = "Not calibrated yet";
  } else if (facts.calibration_passed) {
    summary = "Passed, RMSE " + Meters(facts.calibration_rmse_m);
  } else {
    summary = "Failed, RMSE " + Meters(facts.calibration_rmse_m) + " is too large; calibrate again";
  }
  if (beacons.state != StepState::kDone) {
    return Blocked(Step::kCalibrate, summary, Needs(beacons, BeaconsAction(facts)));
  }
  return ReadyOrDone(Step::kCalibrate,
                     NoBeacons(facts) || (facts.calibration_present && facts.calibration_passed),
                     summary);
}

std::string CalibrateAction(const WorkflowFacts& facts) {
  if (CalibrationFailed(facts)) {
    return "Calibration failed (RMSE " + Meters(facts.calibration_rmse_m) + "): calibrate again";
  }
  return "Calibrate the beacons first";
}

StepStatus EvaluateRecord(const WorkflowFacts& facts, const StepStatus& calibrate) {
  const int min_demos = MinDemos(facts);
  const bool done = facts.demos >= min_demos;
  const std::string summary =
      done ? Count(facts.demos, "demonstration") + ", " + Seconds(facts.demo_seconds)
           : std::to_string(facts.demos) + " of " + Count(min_demos, "demonstration") + " recorded";
  if (calibrate.state != StepState::kDone) {
    return Blocked(Step::kRecord, summary, Needs(calibrate, CalibrateAction(facts)));
  }
  return ReadyOrDone(Step::kRecord, done, summary);
}

StepStatus EvaluatePlay(const WorkflowFacts& facts, const StepStatus& calibrate) {
  // Play data pairs what the camera sees with beacon readings: it only trains RECON's beacon net.
  std::string summary = NoBeacons(facts)         ? "No beacons in this task, so no play data"
                        : facts.play_samples > 0 ? Count(facts.play_samples, "play sample")
                                                 : "No play data yet";
  if (!NoBeacons(facts)) summary += " (optional; improves RECON)";
  if (calibrate.state != StepState::kDone) {
    return Blocked(Step::kPlay, summary, Needs(calibrate, CalibrateAction(facts)));
  }
  return ReadyOrDone(Step::kPlay, NoBeacons(facts) || facts.play_samples > 0, summary);
}

StepStatus EvaluateTrain(const WorkflowFacts& facts, const StepStatus& record) {
  const bool baseline = Contains(facts.trained_methods, kBaselineMethod);
  const bool recon = Contains(facts.trained_methods, kReconMethod);
  std::string summary;
  if (NoBeacons(facts)) {
    summary = std::string(baseline ? "Baseline trained" : "Baseline not trained yet") +
              " (no beacons in this task, so no RECON)";
  } else if (baseline && recon) {
    summary = "Baseline and RECON trained";
  } else if (baseline || recon) {
    summary = baseline ? "Baseline trained; RECON not yet" : "RECON trained; Baseline not yet";
  } else {
    summary = "Nothing trained yet; " + Count(facts.demos, "demonstration") + " and " +
              Count(facts.play_samples, "play sample") + " to train on";
  }
  const int min_demos = MinDemos(facts);
  if (facts.demos < min_demos) {
    const std::string action =
        "Record " + Count(min_demos - facts.demos, "more demonstration") + " first";
    return Blocked(Step::kTrain, summary, Needs(record, action));
  }
  return ReadyOrDone(Step::kTrain, baseline && (recon || NoBeacons(facts)), summary);
}

StepStatus EvaluateRollouts(const WorkflowFacts& facts, const StepStatus& train) {
  // A method whose rollouts are of an older model is as good as not evaluated, and says why.
  std::vector<std::string> not_yet, outdated;
  for (const std::string& method : facts.trained_methods) {
    if (Contains(facts.evaluated_methods, method)) continue;
    (Contains(facts.outdated_evaluations, method) ? outdated : not_yet)
        .push_back(MethodTitle(method));
  }
  const int trained = static_cast<int>(facts.trained_methods.size());
  const int evaluated = trained - static_cast<int>(not_yet.size() + outdated.size());
  std::string summary =
      std::to_string(evaluated) + " of " + Count(trained, "trained method") + " evaluated";
  if (!not_yet.empty()) summary += "; not yet: " + Join(not_yet);
  if (!outdated.empty()) summary += "; out of date: " + Join(outdated);
  if (facts.trained_methods.empty()) {
    const std::string why = facts.training ? Goto("Wait for training to finish", Step::kTrain)
                                           : Needs(train, "Train the Baseline or RECON first");
    return Blocked(Step::kRollouts, summary, why);
  }
  return ReadyOrDone(Step::kRollouts, not_yet.empty() && outdated.empty(), summary);
}

StepStatus EvaluateReport(const WorkflowFacts& facts, const StepStatus& cell,
                          const StepStatus& record) {
  const std::string summary =
      facts.report_written
          ? "Report written"
          : "Not written yet; " + Count(facts.demos, "demonstration") + ", " +
                Count(static_cast<int>(facts.evaluated_methods.size()), "method") + " evaluated";
  if (!facts.session_open) return Blocked(Step::kReport, summary, Needs(cell, CellAction(facts)));
  if (facts.demos < 1) {
    return Blocked(Step::kReport, summary, Needs(record, "Record a demonstration first"));
  }
  return ReadyOrDone(Step::kReport, facts.report_written, summary);
}

/// A step done with the cell itself (Beacons, Calibrate, Record, Play data): blocked in a session
/// taught in another cell, before the steps after it are judged, so that they send the teacher
/// to that reason rather than to a step that cannot be done here.
StepStatus OfThisCell(const WorkflowFacts& facts, StepStatus status) {
  if (facts.taught_elsewhere.empty()) return status;
  status.state = StepState::kBlocked;
  if (!facts.trained_methods.empty()) {
    status.why_blocked =
        facts.taught_elsewhere + "; here, " + Goto("try its policies", Step::kRollouts);
  } else if (facts.demos >= MinDemos(facts)) {
    status.why_blocked = facts.taught_elsewhere + "; here, " + Goto("train it", Step::kTrain);
  } else {
    status.why_blocked = facts.taught_elsewhere + "; too few demonstrations to train here: " +
                         Goto("open another session", Step::kCell);
  }
  return status;
}

/// The steps as their prerequisites alone make them, as if nothing were running.
std::vector<StepStatus> EvaluatePrerequisites(const WorkflowFacts& facts) {
  std::vector<StepStatus> steps;
  steps.reserve(kNumSteps);
  steps.push_back(EvaluateCell(facts));
  steps.push_back(OfThisCell(facts, EvaluateBeacons(facts, steps[Index(Step::kCell)])));
  steps.push_back(OfThisCell(facts, EvaluateCalibrate(facts, steps[Index(Step::kBeacons)])));
  steps.push_back(OfThisCell(facts, EvaluateRecord(facts, steps[Index(Step::kCalibrate)])));
  steps.push_back(OfThisCell(facts, EvaluatePlay(facts, steps[Index(Step::kCalibrate)])));
  steps.push_back(EvaluateTrain(facts, steps[Index(Step::kRecord)]));
  steps.push_back(EvaluateRollouts(facts, steps[Index(Step::kTrain)]));
  steps.push_back(EvaluateReport(facts, steps[Index(Step::kCell)], steps[Index(Step::kRecord)]));
  return steps;
}

/// A running activity: the step it belongs to, the steps it blocks and why.
struct Activity {
  bool running;
  Step step;
  const char* doing;
  std::vector<Step> blocks;
  const char* wait;
};

}  // namespace

const char* StepTitle(Step step) {
  switch (step) {
    case Step::kCell:
      return "Cell";
    case Step::kBeacons:
      return "Beacons";
    case Step::kCalibrate:
      return "Calibrate";
    case Step::kRecord:
      return "Record";
    case Step::kPlay:
      return "Play data";
    case Step::kTrain:
      return "Train";
    case Step::kRollouts:
      return "Rollouts";
    case Step::kReport:
      return "Report";
  }
  return "?";
}

const char* StepPurpose(Step step) {
  switch (step) {
    case Step::kCell:
      return "Open or create a session and connect the camera, the arm, the beacons and the "
             "teleop.";
    case Step::kBeacons:
      return "Stick a beacon on each object that matters and say which object it marks.";
    case Step::kCalibrate:
      return "Check the beacons against the camera's AprilTags so their readings are in the "
             "table frame.";
    case Step::kRecord:
      return "Show the robot the task: drive the arm through it, once per demonstration.";
    case Step::kPlay:
      return "Optionally move the objects around without the arm, so RECON learns more about "
             "them.";
    case Step::kTrain:
      return "Train RECON and the Baseline side by side on what you recorded.";
    case Step::kRollouts:
      return "Remove the beacons and watch each trained policy do the task on its own.";
    case Step::kReport:
      return "Write a report of the session: data, teaching time, training and rollouts.";
  }
  return "";
}

std::vector<StepStatus> EvaluateWorkflow(const WorkflowFacts& facts) {
  std::vector<StepStatus> steps = EvaluatePrerequisites(facts);
  const Activity activities[] = {
      {facts.recording_demos,
       Step::kRecord,
       "Recording now",
       {Step::kBeacons, Step::kCalibrate, Step::kPlay, Step::kTrain},
       "Wait for the demonstration recording to finish or stop it"},
      {facts.recording_play,
       Step::kPlay,
       "Recording now",
       {Step::kBeacons, Step::kCalibrate, Step::kRecord, Step::kTrain},
       "Wait for the play data recording to finish or stop it"},
      {facts.training,
       Step::kTrain,
       "Training now",
       {Step::kRecord, Step::kPlay},
       "Wait for training to finish or cancel it"},
  };
  // Busy first: a running activity is a fact, whatever the other flags say.
  for (const Activity& activity : activities) {
    if (!activity.running) continue;
    StepStatus& status = steps[Index(activity.step)];
    status.state = StepState::kBusy;
    status.summary = std::string(activity.doing) + "; " + status.summary;
    status.why_blocked.clear();
  }
  // A step already blocked keeps its reason: a missing prerequisite outlasts the activity.
  for (const Activity& activity : activities) {
    if (!activity.running) continue;
    for (Step step : activity.blocks) {
      StepStatus& status = steps[Index(step)];
      if (status.state == StepState::kBlocked || status.state == StepState::kBusy) continue;
      status.state = StepState::kBlocked;
      status.why_blocked = Goto(activity.wait, activity.step);
    }
  }
  return steps;
}

Step NextStep(const WorkflowFacts& facts) {
  const std::vector<StepStatus> steps = EvaluateWorkflow(facts);
  for (const StepStatus& status : steps) {
    if (status.state == StepState::kBusy) return status.step;
  }
  for (const StepStatus& status : steps) {
    if (status.state == StepState::kReady && status.step != Step::kPlay) return status.step;
  }
  // Everything done, or nothing to do here (a session taught in another cell without enough
  // demonstrations to train): the report, where it can be written, else another session.
  return steps[Index(Step::kReport)].state == StepState::kBlocked ? Step::kCell : Step::kReport;
}

bool CanOpen(const WorkflowFacts& facts, Step step) {
  if (EvaluateWorkflow(facts)[Index(step)].state != StepState::kBlocked) return true;
  if (Index(step) < Index(NextStep(facts))) return true;
  return EvaluatePrerequisites(facts)[Index(step)].state != StepState::kBlocked;
}

}  // namespace recon::teach
