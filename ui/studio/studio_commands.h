#pragma once

#include <mutex>
#include <string>
#include <variant>
#include <vector>

#include "engine/teach/workflow.h"

namespace recon::ui {

// What the teacher asks for. The screens emit these; the studio's controller drains them on its
// own side and changes the session, the devices and the workers. Plain values, so a test can
// assert on exactly what a click asked for.

struct OpenStep {
  teach::Step step;
};
struct AssignBeacon {
  std::string beacon;
  std::string object;
};
struct StartCalibration {};
struct CancelCalibration {};
struct StartRecording {};
struct StopRecording {};
struct DiscardRecording {};
struct DeleteEpisode {
  std::string name;
};
struct ReRecordEpisode {
  std::string name;
};
struct MarkEpisodeBad {
  std::string name;
  bool bad = true;
};
struct RecordPlay {
  int samples = 30;
};
struct StartTraining {
  std::vector<std::string> methods;
  int steps = 6001;
};
struct CancelTraining {};
struct RunRollouts {
  int tests = 10;
};
struct ShowRolloutFrame {
  std::string method;
  int scenario = 0;
  int frame = 0;
};
struct WriteReport {};
struct DismissErrors {};

using StudioCommand =
    std::variant<OpenStep, AssignBeacon, StartCalibration, CancelCalibration, StartRecording,
                 StopRecording, DiscardRecording, DeleteEpisode, ReRecordEpisode, MarkEpisodeBad,
                 RecordPlay, StartTraining, CancelTraining, RunRollouts, ShowRolloutFrame,
                 WriteReport, DismissErrors>;

/// Commands from the UI thread to the controller; safe to push and drain from different threads.
class CommandQueue {
 public:
  void Push(StudioCommand command) {
    std::lock_guard<std::mutex> lock(mutex_);
    commands_.push_back(std::move(command));
  }
  std::vector<StudioCommand> Drain() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<StudioCommand> out;
    out.swap(commands_);
    return out;
  }

 private:
  std::mutex mutex_;
  std::vector<StudioCommand> commands_;
};

}  // namespace recon::ui
