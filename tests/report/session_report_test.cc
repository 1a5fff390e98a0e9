// The session report: sections, embedded figures, escaping, missing-data hints and errors.
#include "engine/report/session_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/report/html.h"
#include "engine/report/session_figures.h"
#include "tests/report/test_support.h"

namespace recon::report {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::PngImage;
using testing::ReadFile;
using testing::ScratchDir;

const char* const kSectionIds[] = {"overview", "losses", "beacons",      "calibration",
                                   "rollouts", "probe",  "teaching-time"};
const char* const kHeadings[] = {"Overview",
                                 "Training losses",
                                 "Beacon traces",
                                 "Calibration residuals",
                                 "Simulated rollouts: Baseline vs RECON",
                                 "What the policies look at",
                                 "Teaching time"};

SessionReport::LossHistory Run(const std::string& label, bool with_heads) {
  SessionReport::LossHistory run;
  run.label = label;
  run.note = "300 steps, seed 7";
  for (int step = 0; step <= 300; step += 10) {
    const double decay = std::exp(-step / 80.0);
    run.step.push_back(step);
    run.action_loss.push_back(0.02 + 2.0 * decay);
    if (with_heads) {
      run.beacon_loss.push_back(0.01 + 0.5 * decay);
      run.play_loss.push_back(0.03 + 1.0 * decay);
    }
    run.total_loss.push_back(run.action_loss.back() +
                             (with_heads ? run.beacon_loss.back() + run.play_loss.back() : 0));
  }
  return run;
}

SessionReport::BeaconTrace Trace(const std::string& episode, const std::string& beacon) {
  SessionReport::BeaconTrace trace;
  trace.episode = episode;
  trace.beacon = beacon;
  trace.object = beacon + " object";
  trace.unit = "m";
  trace.component_names = {"x", "y"};
  trace.values.resize(2);
  for (int k = 0; k < 80; ++k) {
    trace.values[0].push_back(0.3 + 0.1 * std::sin(k / 10.0));
    trace.values[1].push_back(-0.2 + 0.05 * k / 80.0);
  }
  return trace;
}

SessionReport FullReport() {
  SessionReport report;
  report.title = "Teaching session: tabletop";
  report.session_path = "/data/sessions/tabletop-1";
  report.facts = {{"world", "tabletop"}, {"episodes", "4 demonstrations"}, {"beacons", "2"}};
  report.losses = {Run("RECON", true), Run("Baseline", false)};
  report.beacon_traces = {Trace("demo_1", "plate"), Trace("demo_2", "toast")};
  auto& cal = report.calibration;
  cal.present = true;
  cal.rmse_m = 0.031;
  cal.mean_m = 0.027;
  cal.median_m = 0.025;
  cal.p95_m = 0.06;
  cal.threshold_m = 0.10;
  cal.passed = true;
  cal.residual_m = {0.02, 0.03, 0.025, 0.018, 0.21, 0.04, 0.022, 0.035, 0.17, 0.028};
  cal.inlier = {true, true, true, true, false, true, true, true, false, true};
  SessionReport::Rollout recon;
  recon.label = "RECON";
  recon.metric_name = "final distance of the toast to the plate (m)";
  recon.metric_mean = 0.052;
  recon.metric_sem = 0.01;
  recon.tests = 20;
  recon.has_success = true;
  recon.success_rate = 0.85;
  recon.success_sem = 0.08;
  recon.details = {{"mean episode length (s)", 12.5}};
  recon.note = "20 test scenarios";
  SessionReport::Rollout baseline = recon;
  baseline.label = "Baseline";
  baseline.metric_mean = 0.143;
  baseline.metric_sem = 0.021;
  baseline.success_rate = 0.45;
  baseline.success_sem = 0.11;
  report.rollouts = {baseline, recon};
  report.ledger = {{"Baseline (4 demos)", 180, 0, 0, 180, 190.0},
                   {"RECON (4 demos + beacons)", 180, 45, 0, 225, 240.0},
                   {"RECON (Play)", 60, 45, 300, 405, std::nullopt}};
  report.ledger_note = "Times measured by the recorder.";
  SessionReport::Probe probe;
  probe.rows = {{"Baseline", "bowl", 0.0054, 0.128, 0.21, 0.35},
                {"RECON (Play)", "bowl", 0.0003, 0.012, -0.06, 0.9},
                {"RECON (Play)", "toast", 0.0004, 0.005, std::nullopt, std::nullopt}};
  HeatMap map;
  map.title = "RECON (Play): the bowl moved";
  map.nx = 3;
  map.ny = 2;
  map.x_min = 0.22;
  map.x_max = 0.82;
  map.y_min = -0.5;
  map.y_max = 0.5;
  map.values = {0.001, 0.002, NAN, 0.0, 0.004, 0.003};
  map.robot_view = true;
  map.markers = {{0.4, -0.2, "bowl (home)"}, {0.56, 0.33, "plate"}};
  probe.maps = {map};
  probe.note = "Objects moved one at a time over a 3 x 2 grid.";
  report.probe = probe;
  return report;
}

// An independent decoder, so the test does not trust the encoder it checks.
std::string DecodeBase64(const std::string& text) {
  const std::string kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    const size_t value = kAlphabet.find(c);
    if (value == std::string::npos) throw std::runtime_error(std::string("bad base64: ") + c);
    buffer = buffer << 6 | static_cast<uint32_t>(value);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((buffer >> bits) & 0xFF);
    }
  }
  return out;
}

// data-file attribute -> decoded bytes of the image's data: URI, for every <img>.
std::map<std::string, std::string> EmbeddedImages(const std::string& html) {
  std::map<std::string, std::string> images;
  const std::string prefix = "<img src=\"data:image/png;base64,";
  for (size_t at = html.find("<img"); at != std::string::npos; at = html.find("<img", at + 1)) {
    EXPECT_EQ(html.compare(at, prefix.size(), prefix), 0) << html.substr(at, 80);
    const size_t start = at + prefix.size();
    const size_t end = html.find('"', start);
    const size_t file_at = html.find("data-file=\"", end) + 11;
    const std::string file = html.substr(file_at, html.find('"', file_at) - file_at);
    images[file] = DecodeBase64(html.substr(start, end - start));
  }
  return images;
}

std::set<std::string> Files(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

TEST(SessionReportTest, FullReportHasEverySectionInOrder) {
  ScratchDir dir("full_sections");
  WriteSessionReport(FullReport(), dir.File("out"));
  const std::string html = ReadFile(dir.File("out/report.html"));
  size_t previous = 0;
  for (size_t i = 0; i < std::size(kSectionIds); ++i) {
    const std::string tag = "<section id=\"" + std::string(kSectionIds[i]) + "\">\n<h2>" +
                            EscapeHtml(kHeadings[i]) + "</h2>";
    const size_t at = html.find(tag);
    ASSERT_NE(at, std::string::npos) << tag;
    EXPECT_GT(at, previous) << kSectionIds[i] << " is out of order";
    previous = at;
  }
  EXPECT_THAT(html, Not(HasSubstr("class=\"missing\"")));
  EXPECT_THAT(html, HasSubstr("/data/sessions/tabletop-1"));
  EXPECT_THAT(html, HasSubstr("PASS"));
  EXPECT_THAT(html, HasSubstr("0.031 m"));
  EXPECT_THAT(html, HasSubstr("85% &plusmn; 8%"));
  EXPECT_THAT(html, HasSubstr("405 s (6:45)"));
  EXPECT_THAT(html, HasSubstr("Times measured by the recorder."));
}

TEST(SessionReportTest, FiguresAreWrittenAndDecode) {
  ScratchDir dir("full_figures");
  const std::vector<std::string> written = WriteSessionReport(FullReport(), dir.File("out"));
  ASSERT_FALSE(written.empty());
  EXPECT_EQ(written.back(), dir.File("out/report.html"));
  const std::set<std::string> expected = {"losses.png",
                                          "beacon_1_demo_1_plate.png",
                                          "beacon_2_demo_2_toast.png",
                                          "calibration.png",
                                          "rollouts_metric_1.png",
                                          "rollouts_success.png",
                                          "teaching_time.png",
                                          "probe_RECON__Play___the_bowl_moved.png"};
  EXPECT_EQ(Files(dir.File("out/figures")), expected);
  EXPECT_EQ(Files(dir.File("out")), (std::set<std::string>{"figures", "report.html"}));
  ASSERT_EQ(written.size(), expected.size() + 1);
  for (size_t i = 0; i + 1 < written.size(); ++i) {
    SCOPED_TRACE(written[i]);
    const PngImage image(written[i]);
    EXPECT_EQ(image.width(), 2 * FigureFiles::kWidth);
    EXPECT_GT(image.DistinctColors(), 50u);
    const size_t white = image.CountNear({1, 1, 1}, 2);
    const size_t pixels = static_cast<size_t>(image.width()) * image.height();
    EXPECT_GT(pixels - white, pixels / 50) << "almost blank";
  }
}

TEST(SessionReportTest, TheProbeShowsWholeRolloutsOrARealCellsReadOutWithNothingMoved) {
  ScratchDir dir("probe_kinds");
  SessionReport rolled = FullReport();
  HeatMap outcome = rolled.probe->maps.front();
  outcome.title = "Baseline: whole rollouts, the bowl moved";
  outcome.values = {1, 0, NAN, 1, 1, 0};
  outcome.scale_max = 1;
  rolled.probe->outcome_maps = {outcome};
  rolled.probe->verdicts = {"Baseline succeeds from 35 % of the bowl's places"};
  WriteSessionReport(rolled, dir.File("rolled"));
  std::string html = ReadFile(dir.File("rolled/report.html"));
  EXPECT_THAT(html, HasSubstr("Rollouts succeeded"));
  EXPECT_THAT(html, HasSubstr("90 %"));  // RECON (Play) with the bowl moved
  EXPECT_THAT(html, HasSubstr("succeeds from 35 %"));
  EXPECT_TRUE(
      fs::exists(dir.File("rolled/figures/probe_Baseline__whole_rollouts__the_bowl_moved.png")));

  // A real cell's session: only the read-out, on recorded frames; no grid, no map.
  SessionReport real = FullReport();
  real.probe->rows = {{"RECON", "plate", std::nullopt, std::nullopt, 0.93, std::nullopt}};
  real.probe->maps.clear();
  real.probe->note = "Read out on 400 recorded frames of 8 episodes.";
  WriteSessionReport(real, dir.File("real"));
  html = ReadFile(dir.File("real/report.html"));
  EXPECT_THAT(html, HasSubstr("taught on a real cell"));
  EXPECT_THAT(html, HasSubstr("0.93"));
  EXPECT_THAT(html, Not(HasSubstr("Rollouts succeeded")));
  EXPECT_FALSE(fs::exists(dir.File("real/figures/probe_RECON__Play___the_bowl_moved.png")));
}

TEST(SessionReportTest, EmbeddedImagesAreTheFigureFiles) {
  ScratchDir dir("embedded");
  const std::vector<std::string> written = WriteSessionReport(FullReport(), dir.File("out"));
  const std::map<std::string, std::string> images =
      EmbeddedImages(ReadFile(dir.File("out/report.html")));
  ASSERT_EQ(images.size(), written.size() - 1);
  for (const auto& [file, bytes] : images) {
    SCOPED_TRACE(file);
    const std::string on_disk = ReadFile(dir.File("out/" + file));
    ASSERT_GT(on_disk.size(), 1000u);
    EXPECT_TRUE(bytes == on_disk) << "the data: URI differs from the PNG file";
  }
}

TEST(SessionReportTest, HtmlIsSelfContained) {
  ScratchDir dir("self_contained");
  WriteSessionReport(FullReport(), dir.File("out"));
  const std::string html = ReadFile(dir.File("out/report.html"));
  for (const char* reference :
       {"http://", "https://", "<script", "<link", "@import", "url(", "src=\"figures", "src=\"/"}) {
    EXPECT_THAT(html, Not(HasSubstr(reference)));
  }
  EXPECT_THAT(html, HasSubstr("<style>"));
  EXPECT_THAT(html, HasSubstr("<meta charset=\"utf-8\">"));
}

TEST(SessionReportTest, TextIsEscaped) {
  SessionReport report = FullReport();
  report.title = "Session <b>bold</b>";
  report.facts.push_back({"operator", "Tom & Jerry"});
  report.rollouts[0].label = "<script>alert('x')</script>";
  report.beacon_traces[0].beacon = "\"quoted\"";
  ScratchDir dir("escaped");
  WriteSessionReport(report, dir.File("out"));
  const std::string html = ReadFile(dir.File("out/report.html"));
  EXPECT_THAT(html, Not(HasSubstr("<script")));
  EXPECT_THAT(html, Not(HasSubstr("<b>bold")));
  EXPECT_THAT(html, HasSubstr("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"));
  EXPECT_THAT(html, HasSubstr("Session &lt;b&gt;bold&lt;/b&gt;"));
  EXPECT_THAT(html, HasSubstr("Tom &amp; Jerry"));
  EXPECT_THAT(html, HasSubstr("&quot;quoted&quot;"));
}

TEST(SessionReportTest, EmptyReportExplainsWhatIsMissing) {
  ScratchDir dir("empty");
  const std::vector<std::string> written = WriteSessionReport(SessionReport{}, dir.File("out"));
  EXPECT_EQ(written, std::vector<std::string>{dir.File("out/report.html")});
  const std::string html = ReadFile(dir.File("out/report.html"));
  for (const char* id : kSectionIds) {
    const size_t at = html.find("<section id=\"" + std::string(id) + "\">");
    ASSERT_NE(at, std::string::npos) << id;
    const size_t end = html.find("</section>", at);
    EXPECT_THAT(html.substr(at, end - at), HasSubstr("class=\"missing\"")) << id;
  }
  for (const char* command :
       {"recon train --session DIR", "recon calibrate --sim --out cal.json",
        "recon record ... --calibration cal.json", "recon eval --session DIR"}) {
    EXPECT_THAT(html, HasSubstr("<code>" + std::string(command) + "</code>"));
  }
  EXPECT_THAT(html, HasSubstr("No training yet"));
  EXPECT_THAT(html, Not(HasSubstr("<img")));
  EXPECT_TRUE(Files(dir.File("out/figures")).empty());
}

TEST(SessionReportTest, UnwritableFolderIsAUserErrorNamingIt) {
  ScratchDir dir("unwritable");
  { std::ofstream(dir.File("plain_file")) << "not a folder"; }
  const std::string out = dir.File("plain_file/report");
  try {
    WriteSessionReport(FullReport(), out);
    FAIL() << "no UserError";
  } catch (const UserError& error) {
    EXPECT_THAT(error.what(), HasSubstr(out));
  }
  EXPECT_EQ(dir.Entries(), std::set<std::string>{"plain_file"});
}

TEST(SessionReportTest, MismatchedLossColumnsNameTheField) {
  SessionReport report = FullReport();
  report.losses[0].beacon_loss.pop_back();
  ScratchDir dir("mismatch");
  try {
    WriteSessionReport(report, dir.File("out"));
    FAIL() << "no UserError";
  } catch (const UserError& error) {
    EXPECT_THAT(error.what(), HasSubstr("losses[0] ('RECON').beacon_loss"));
  }
  EXPECT_FALSE(fs::exists(dir.File("out/report.html")));
}

TEST(SessionReportTest, DivergedRunIsDrawnUpToTheNaNs) {
  SessionReport report = FullReport();
  auto& run = report.losses[1];
  for (size_t k = run.step.size() - 3; k < run.step.size(); ++k) {
    run.action_loss[k] = NAN;
    run.total_loss[k] = INFINITY;
  }
  ScratchDir dir("diverged");
  WriteSessionReport(report, dir.File("out"));
  EXPECT_THAT(ReadFile(dir.File("out/report.html")), HasSubstr("6 NaN/infinite values not drawn"));
  EXPECT_GT(PngImage(dir.File("out/figures/losses.png")).DistinctColors(), 50u);
}

TEST(SessionReportTest, CalibrationColoursOutliersApart) {
  ScratchDir dir("calibration");
  SessionReport report;
  report.calibration = FullReport().calibration;
  WriteSessionReport(report, dir.File("with_outliers"));
  const PngImage with(dir.File("with_outliers/figures/calibration.png"));
  EXPECT_GT(with.CountNear(InlierColor(), 3), 2000u);
  EXPECT_GT(with.CountNear(OutlierColor(), 3), 1000u);

  report.calibration.inlier.assign(report.calibration.residual_m.size(), true);
  report.calibration.passed = false;
  WriteSessionReport(report, dir.File("all_inliers"));
  const PngImage without(dir.File("all_inliers/figures/calibration.png"));
  EXPECT_EQ(without.CountNear(OutlierColor(), 3), 0u);
  EXPECT_THAT(ReadFile(dir.File("all_inliers/report.html")), HasSubstr("FAIL"));
}

TEST(SessionReportTest, PaperTotalsGetTheirOwnLighterBars) {
  ScratchDir dir("ledger");
  SessionReport report;
  report.ledger = FullReport().ledger;
  WriteSessionReport(report, dir.File("out"));
  const PngImage image(dir.File("out/figures/teaching_time.png"));
  // Rows 0 and 1 have a paper total, row 2 does not.
  EXPECT_GT(image.CountNear(Lighter(RowColor(0)), 3), 2000u);
  EXPECT_GT(image.CountNear(Lighter(RowColor(1)), 3), 2000u);
  EXPECT_EQ(image.CountNear(Lighter(RowColor(2)), 3), 0u);
  const std::string html = ReadFile(dir.File("out/report.html"));
  EXPECT_THAT(html, HasSubstr("190 s (3:10)"));
  EXPECT_THAT(html, HasSubstr("&minus;10.0 s"));
}

TEST(SessionReportTest, RolloutsWithoutSuccessHaveNoSuccessFigure) {
  SessionReport report = FullReport();
  for (auto& rollout : report.rollouts) rollout.has_success = false;
  report.rollouts[1].metric_name = "another metric";
  ScratchDir dir("no_success");
  WriteSessionReport(report, dir.File("out"));
  const std::set<std::string> figures = Files(dir.File("out/figures"));
  EXPECT_FALSE(figures.count("rollouts_success.png"));
  // Two metrics cannot share an axis: one chart each.
  EXPECT_TRUE(figures.count("rollouts_metric_1.png"));
  EXPECT_TRUE(figures.count("rollouts_metric_2.png"));
}

TEST(SessionReportTest, RewritingRemovesStaleFiguresOnly) {
  ScratchDir dir("rewrite");
  const std::string out = dir.File("out");
  WriteSessionReport(FullReport(), out);
  { std::ofstream(out + "/figures/notes.txt") << "mine"; }
  WriteSessionReport(SessionReport{}, out);
  EXPECT_EQ(Files(out + "/figures"), std::set<std::string>{"notes.txt"});
  EXPECT_EQ(Files(out), (std::set<std::string>{"figures", "report.html"}));
  EXPECT_THAT(ReadFile(out + "/report.html"), HasSubstr("No training yet"));
}

TEST(HtmlTest, EscapesMarkupCharacters) {
  EXPECT_EQ(EscapeHtml("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
  EXPECT_EQ(EscapeHtml("plain text \u00b1"), "plain text \u00b1");
}

TEST(HtmlTest, Base64MatchesTheRfcVectors) {
  // RFC 4648, section 10.
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  std::string all_bytes;
  for (int b = 0; b < 256; ++b) all_bytes += static_cast<char>(b);
  EXPECT_TRUE(DecodeBase64(Base64(all_bytes)) == all_bytes);
}

TEST(HtmlTest, NumbersHaveAboutThreeSignificantDigits) {
  EXPECT_EQ(FormatNumber(6001), "6001");
  EXPECT_EQ(FormatNumber(0.05234), "0.0523");
  EXPECT_EQ(FormatNumber(1.2345), "1.23");
  EXPECT_EQ(FormatNumber(-42.42), "-42.4");
  EXPECT_EQ(FormatNumber(0), "0");
  EXPECT_EQ(FormatNumber(3), "3");
  EXPECT_EQ(FormatNumber(-12), "-12");
  EXPECT_EQ(FormatNumber(1.5e-6), "1.50e-06");
  EXPECT_EQ(FormatNumber(NAN), "n/a");
  EXPECT_EQ(FormatFixed(INFINITY, 2), "n/a");
}

}  // namespace
}  // namespace recon::report
