// Opens a generated session report in headless Chromium and checks what a reader would see: a
// full, non-blank page whose figures loaded and whose sections are all there.
//
// To look at the report yourself, keep the output (report, screenshot, dumped DOM):
//   RECON_KEEP_REPORT=/tmp/session-report build/<preset>/tests/report/report_browser_test
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "engine/report/chart.h"
#include "engine/report/session_report.h"
#include "tests/report/test_support.h"

namespace recon::report {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::PngImage;
using testing::ReadFile;
using testing::ScratchDir;

constexpr int kWindowWidth = 1200;
constexpr int kWindowHeight = 5000;
constexpr std::chrono::seconds kChromiumTimeout{60};

// ---------------------------------------------------------------------------------------------
// Synthetic data shaped like a real tabletop session.

SessionReport::LossHistory LossRun(const std::string& label, bool recon, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 0.15);
  SessionReport::LossHistory run;
  run.label = label;
  run.note = "6001 steps, seed " + std::to_string(seed) + (recon ? ", 41 s" : ", 23 s");
  for (int step = 0; step <= 6000; step += 20) {
    const double decay = std::exp(-step / 900.0);
    auto noisy = [&](double value) { return value * std::exp(noise(rng)); };
    run.step.push_back(step);
    run.action_loss.push_back(noisy(0.02 + 1.5 * decay));
    double total = run.action_loss.back();
    if (recon) {
      run.beacon_loss.push_back(noisy(0.004 + 0.6 * decay));
      run.play_loss.push_back(noisy(0.03 + 0.9 * decay));
      total += run.beacon_loss.back() + run.play_loss.back();
    }
    run.total_loss.push_back(total);
  }
  return run;
}

SessionReport::BeaconTrace Trace(const std::string& episode, const std::string& beacon,
                                 const std::string& object, double phase) {
  SessionReport::BeaconTrace trace;
  trace.episode = episode;
  trace.beacon = beacon;
  trace.object = object;
  trace.unit = "m";
  trace.step_seconds = 0.1;
  trace.component_names = {"x", "y"};
  trace.values.resize(2);
  for (int k = 0; k < 120; ++k) {
    const double t = k * 0.1;
    const double reach = 1 / (1 + std::exp(-(t - 5 - phase)));
    trace.values[0].push_back(0.42 - 0.25 * reach + 0.004 * std::sin(7 * t));
    trace.values[1].push_back(-0.1 + 0.18 * reach + 0.004 * std::cos(5 * t));
  }
  // A dropout, as when the beacon is briefly occluded.
  for (int k = 40; k < 44; ++k) trace.values[0][k] = trace.values[1][k] = NAN;
  return trace;
}

SessionReport ExampleReport() {
  SessionReport report;
  report.title = "Teaching session: tabletop";
  report.session_path = "/home/operator/sessions/tabletop-2024-05-01";
  report.generated = "2024-05-01 14:03 UTC";
  report.facts = {{"World", "tabletop (toast on a plate)"},
                  {"Created", "2024-05-01 13:20"},
                  {"Episodes", "4 demonstrations, 1 play session"},
                  {"Play samples", "3000 (5 min at 10 Hz)"},
                  {"Seeds", "7 (training), 100-119 (tests)"},
                  {"Devices", "simulated UWB anchors x4, simulated arm"},
                  {"Beacons", "plate, toast"}};
  report.losses = {LossRun("RECON", true, 7), LossRun("Baseline", false, 7)};
  report.beacon_traces = {Trace("demo_1", "plate", "the plate", 0),
                          Trace("demo_1", "toast", "the toast", 1.5),
                          Trace("demo_2", "toast", "the toast", -1)};
  auto& cal = report.calibration;
  cal.present = true;
  cal.residual_m = {0.021, 0.034, 0.018, 0.027, 0.045, 0.012,
                    0.19,  0.031, 0.024, 0.038, 0.016, 0.029};
  cal.inlier.assign(cal.residual_m.size(), true);
  cal.inlier[6] = false;
  cal.rmse_m = 0.028;
  cal.mean_m = 0.027;
  cal.median_m = 0.027;
  cal.p95_m = 0.043;
  cal.threshold_m = 0.10;
  cal.passed = true;
  SessionReport::Rollout baseline;
  baseline.label = "Baseline";
  baseline.metric_name = "final distance of the toast to the plate (m)";
  baseline.metric_mean = 0.143;
  baseline.metric_sem = 0.021;
  baseline.tests = 20;
  baseline.has_success = true;
  baseline.success_rate = 0.45;
  baseline.success_sem = 0.11;
  baseline.details = {{"mean episode length (s)", 14.2}, {"collisions", 3}};
  baseline.note = "20 test scenarios, seeds 100-119";
  SessionReport::Rollout recon = baseline;
  recon.label = "RECON";
  recon.metric_mean = 0.052;
  recon.metric_sem = 0.010;
  recon.success_rate = 0.85;
  recon.success_sem = 0.08;
  recon.details = {{"mean episode length (s)", 11.8}, {"collisions", 1}};
  report.rollouts = {baseline, recon};
  report.ledger = {{"Baseline (4 demos)", 212, 0, 0, 212, 240.0},
                   {"RECON (4 demos + beacons)", 212, 38, 0, 250, 270.0},
                   {"RECON (Play)", 60, 38, 300, 398, 420.0},
                   {"Baseline (8 demos)", 431, 0, 0, 431, std::nullopt}};
  report.ledger_note =
      "Measured by the recorder from the first to the last sample of each "
      "episode; beacon placement from the placement prompts.";
  return report;
}

// ---------------------------------------------------------------------------------------------
// Running Chromium.

std::string FindChromium() {
  if (const char* path = std::getenv("RECON_CHROMIUM"); path && *path) return path;
  const char* path_env = std::getenv("PATH");
  std::string paths = path_env ? path_env : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= paths.size()) {
    const size_t end = std::min(paths.find(':', start), paths.size());
    const fs::path candidate = fs::path(paths.substr(start, end - start)) / "chromium";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return "";
}

struct Outcome {
  bool timed_out = false;
  int exit_code = -1;
  std::string stderr_tail;  ///< for failure messages only: Chromium's stderr is full of noise
};

// Runs `argv` with stdout to `stdout_path`, in its own process group so that on timeout the
// whole group (Chromium's helper processes too) is killed.
Outcome Run(const std::vector<std::string>& argv, const std::string& stdout_path,
            const std::string& stderr_path) {
  std::vector<char*> args;
  for (const auto& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  Outcome outcome;
  if (pid < 0) return outcome;
  ::setpgid(pid, pid);  // also here, so the group exists whichever process runs first
  const auto deadline = std::chrono::steady_clock::now() + kChromiumTimeout;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      outcome.timed_out = true;
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  // Helpers that outlive the browser process would hold the scratch folder open.
  ::kill(-pid, SIGKILL);
  if (!outcome.timed_out && WIFEXITED(status)) outcome.exit_code = WEXITSTATUS(status);
  const std::string err = ReadFile(stderr_path);
  outcome.stderr_tail = err.substr(err.size() > 2000 ? err.size() - 2000 : 0);
  return outcome;
}

// Where the report, screenshot and DOM go: RECON_KEEP_REPORT if set (kept), else a scratch
// folder removed at the end. Chromium's profile always goes to scratch.
class BrowserRun {
 public:
  explicit BrowserRun(const std::string& name) : scratch_(std::make_unique<ScratchDir>(name)) {
    const char* keep = std::getenv("RECON_KEEP_REPORT");
    out_dir_ = fs::absolute(keep && *keep ? std::string(keep) : scratch_->File("report")).string();
    figures_ = WriteSessionReport(ExampleReport(), out_dir_);
    figures_.pop_back();  // report.html
    report_ = Output("report.html");
  }

  // Runs Chromium headless on `page` with `mode` (--screenshot=... or --dump-dom); fails the
  // test with the reason when it cannot.
  void Chromium(const std::string& mode, const std::string& page, const std::string& stdout_path) {
    const std::string chromium = FindChromium();
    ASSERT_FALSE(chromium.empty()) << "chromium is not installed (not on PATH, RECON_CHROMIUM "
                                      "unset): run scripts/install-deps";
    const std::vector<std::string> argv = {
        chromium,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--hide-scrollbars",
        "--force-device-scale-factor=1",
        "--window-size=" + std::to_string(kWindowWidth) + "," + std::to_string(kWindowHeight),
        "--no-first-run",
        "--disable-extensions",
        "--disable-breakpad",
        "--user-data-dir=" + scratch_->File("profile"),
        "--disk-cache-dir=" + scratch_->File("cache"),
        mode,
        "file://" + page};
    const Outcome outcome = Run(argv, stdout_path, scratch_->File("chromium.stderr"));
    ASSERT_FALSE(outcome.timed_out) << chromium << " did not finish within "
                                    << kChromiumTimeout.count() << " s; its stderr ends with:\n"
                                    << outcome.stderr_tail;
    ASSERT_EQ(outcome.exit_code, 0) << chromium << " failed; its stderr ends with:\n"
                                    << outcome.stderr_tail;
  }

  std::string Output(const std::string& name) const { return (fs::path(out_dir_) / name).string(); }
  const std::string& report() const { return report_; }
  const std::vector<std::string>& figures() const { return figures_; }

 private:
  std::unique_ptr<ScratchDir> scratch_;
  std::string out_dir_, report_;
  std::vector<std::string> figures_;
};

// The report with a script added that, once the page has loaded, records in the DOM what the
// browser made of each image; the report itself has no scripts, so this is a separate page.
std::string WriteProbePage(const std::string& report_path) {
  std::string html = ReadFile(report_path);
  const size_t body_end = html.rfind("</body>");
  EXPECT_NE(body_end, std::string::npos);
  html.insert(body_end, R"(<script>
window.addEventListener('load', () => {
  for (const img of document.images) {
    const r = img.getBoundingClientRect();
    img.dataset.probe = [img.complete ? 1 : 0, img.naturalWidth, img.naturalHeight,
                         Math.round(r.width), Math.round(r.height)].join(',');
  }
  document.body.dataset.probeDone = 'yes';
});
</script>
)");
  const std::string probe = (fs::path(report_path).parent_path() / "probe.html").string();
  std::ofstream(probe) << html;
  return probe;
}

// The value of `name`="..." in an HTML start tag; empty when absent.
std::string Attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t start = tag.find(key);
  if (start == std::string::npos) return "";
  const size_t value = start + key.size();
  return tag.substr(value, tag.find('"', value) - value);
}

TEST(ReportBrowserTest, ScreenshotShowsAFullPageWithCharts) {
  BrowserRun run("browser_screenshot");
  const std::string screenshot = run.Output("screenshot.png");
  fs::remove(screenshot);
  ASSERT_NO_FATAL_FAILURE(
      run.Chromium("--screenshot=" + screenshot, run.report(), run.Output("chromium.stdout")));
  ASSERT_TRUE(fs::exists(screenshot)) << "Chromium wrote no screenshot";
  const PngImage image(screenshot);
  EXPECT_EQ(image.width(), kWindowWidth);
  EXPECT_EQ(image.height(), kWindowHeight);

  // Text, tables and anti-aliased charts give thousands of colours; a blank or unstyled page
  // gives a handful.
  EXPECT_GT(image.DistinctColors(), 5000u);
  const size_t pixels = static_cast<size_t>(image.width()) * image.height();
  const size_t white = image.CountNear({1, 1, 1}, 4);
  EXPECT_GT(pixels - white, pixels / 20) << "the page is mostly blank";

  // The page's own styles use no palette colour, so these pixels come from the figures: the
  // loss curves, the calibration bars and the beacon traces.
  EXPECT_GT(image.CountNear(PaletteColor(0), 12), 5000u) << "no chart blue on the page";
  EXPECT_GT(image.CountNear(PaletteColor(1), 12), 2000u) << "no chart orange on the page";
}

TEST(ReportBrowserTest, RenderedDomHasEverySectionAndLoadedFigure) {
  BrowserRun run("browser_dom");
  const std::string probe = WriteProbePage(run.report());
  const std::string dom_path = run.Output("dom.html");
  ASSERT_NO_FATAL_FAILURE(run.Chromium("--dump-dom", probe, dom_path));
  const std::string dom = ReadFile(dom_path);
  ASSERT_THAT(dom, HasSubstr("data-probe-done=\"yes\"")) << "the page never finished loading";

  for (const char* heading :
       {"Overview", "Training losses", "Beacon traces", "Calibration residuals",
        "Simulated rollouts: Baseline vs RECON", "What the policies look at", "Teaching time"}) {
    EXPECT_THAT(dom, HasSubstr("<h2>" + std::string(heading) + "</h2>"));
  }
  for (const char* id :
       {"overview", "losses", "beacons", "calibration", "rollouts", "probe", "teaching-time"}) {
    EXPECT_THAT(dom, HasSubstr("<section id=\"" + std::string(id) + "\">"));
  }

  // Every figure file is shown once, decoded at its full size and laid out at a visible size.
  // Parsed by hand: std::regex recurses per character and overflows the stack on the
  // megabytes of base64 in each tag.
  std::map<std::string, std::string> probes;
  for (size_t at = dom.find("<img"); at != std::string::npos; at = dom.find("<img", at + 1)) {
    const std::string tag = dom.substr(at, dom.find('>', at) - at);
    probes[Attribute(tag, "data-file")] = Attribute(tag, "data-probe");
  }
  ASSERT_EQ(probes.size(), run.figures().size());
  for (const std::string& figure : run.figures()) {
    const std::string file = "figures/" + fs::path(figure).filename().string();
    SCOPED_TRACE(file);
    ASSERT_TRUE(probes.count(file)) << "no <img> for this figure";
    int complete = 0, natural_w = 0, natural_h = 0, shown_w = 0, shown_h = 0;
    ASSERT_EQ(std::sscanf(probes[file].c_str(), "%d,%d,%d,%d,%d", &complete, &natural_w, &natural_h,
                          &shown_w, &shown_h),
              5);
    const PngImage png(figure);
    EXPECT_EQ(complete, 1);
    EXPECT_EQ(natural_w, png.width()) << "the browser did not decode the embedded PNG";
    EXPECT_EQ(natural_h, png.height());
    EXPECT_GT(shown_w, 800);
    EXPECT_NEAR(static_cast<double>(shown_h) / shown_w,
                static_cast<double>(png.height()) / png.width(), 0.01);
  }
}

}  // namespace
}  // namespace recon::report
