#pragma once

// A short teaching session played into the real recon-studio by the fault tests (StudioFaultTest,
// StudioDiskFullTest): mark the plate, calibrate, record a demonstration and play data, train
// both methods, roll out, write the report; each step's wait generous so that only a failure
// stops it.

namespace recon::testing {

constexpr const char* kStudioTeachingScript =
    "click Beacons##step\nclick object:plate\nwait-idle 30\n"
    "click Calibrate##step\nclick Collect points and fit\nwait-idle 300\n"
    "click Record##step\nclick Start recording\nwait-idle 300\n"
    "click Play data##step\nclick Record 30 play samples\nwait-idle 120\n"
    "click Train##step\nclick Train Baseline and RECON\nwait-idle 600\n"
    "click Rollouts##step\nclick Run rollouts\nwait-idle 600\n"
    "click Report##step\nclick Write the report\nwait-idle 120\n";

/// The studio's arguments for it (@S: the session, @R: the run's root, with the script at
/// @R/extra/teach.script); short training and two rollout scenes keep a run to 10-20 s.
constexpr const char* kStudioTeachingArgs =
    "--headless --fast --session @S --train-steps 20 --rollout-tests 2 --script "
    "@R/extra/teach.script";

/// The studio keeps its home, temporary files and list of recent sessions in the run's folder.
constexpr const char* kStudioEnvironment =
    "HOME=@R/home XDG_CONFIG_HOME=@R/config MESA_SHADER_CACHE_DISABLE=true ";

}  // namespace recon::testing
