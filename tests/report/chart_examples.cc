// Writes example charts into the folder given on the command line, for a person to look at.
#include <cmath>
#include <cstdio>
#include <exception>
#include <random>
#include <string>

#include "engine/report/chart.h"
#include "tests/report/test_support.h"

namespace recon::report {
namespace {

LineChart LossCurves() {
  LineChart chart;
  chart.title = "Training loss";
  chart.subtitle = "Dynamic 2D, seed 1; 6000 optimiser steps";
  chart.x_label = "step";
  chart.y_label = "loss (log scale)";
  chart.log_y = true;
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 1);
  const struct {
    const char* name;
    double start, floor, rate, jitter;
  } kCurves[] = {{"RECON", 4.0, 0.004, 900, 0.25},
                 {"Baseline", 3.0, 0.02, 1400, 0.2},
                 {"RECON (beacon head)", 0.8, 0.0015, 700, 0.3}};
  for (const auto& curve : kCurves) {
    LineChart::Series series;
    series.name = curve.name;
    series.markers = false;
    for (int step = 0; step < 6000; ++step) {
      const double mean = curve.floor + curve.start * std::exp(-step / curve.rate);
      series.x.push_back(step);
      series.y.push_back(mean * std::exp(curve.jitter * noise(rng)));
    }
    chart.series.push_back(series);
  }
  return chart;
}

LineChart DataEfficiency() {
  LineChart chart;
  chart.title = "Data efficiency";
  chart.subtitle = "mean over 15 seeds; bands show the standard error";
  chart.x_label = "demonstrations";
  chart.y_label = "episode return";
  const char* names[] = {"RECON", "Baseline"};
  for (int i = 0; i < 2; ++i) {
    LineChart::Series series;
    series.name = names[i];
    series.x = {5, 10, 20, 40, 80};
    for (const double x : series.x) {
      series.y.push_back(17 - (6 + 2 * i) * std::exp(-x / (15 + 10 * i)));
      series.errors.push_back(0.6 * std::exp(-x / 60) + 0.2);
    }
    chart.series.push_back(series);
  }
  chart.references = {{17.79, "expert 17.79"}, {10.0, "standing still 10.0"}};
  return chart;
}

// Many bars with long names: the labels have to rotate to stay apart.
BarChart ManyLongLabels() {
  BarChart chart;
  chart.title = "Bin transfer: success rate by condition (ablation over beacon placement)";
  chart.y_label = "success rate";
  for (int i = 0; i < 16; ++i) {
    chart.labels.push_back("RECON_with_beacons_on_" + std::string(i % 2 ? "gripper" : "bin") +
                           "_seed_group_" + std::to_string(i));
    chart.values.push_back(0.35 + 0.035 * i);
    chart.errors.push_back(0.04);
  }
  chart.references = {{0.93, "expert"}};
  return chart;
}

// Log y with zeros, negatives and error bands reaching below zero: the awkward case.
LineChart NonPositiveLogY() {
  LineChart chart = LossCurves();
  chart.title = "Log axis with non-positive values";
  chart.subtitle = "zeros and negatives are skipped; band edges below zero clamp to the axis";
  chart.series.resize(2);
  for (size_t k = 0; k < chart.series[0].y.size(); ++k) {
    if (k % 1000 == 500) chart.series[0].y[k] = 0;
    if (k % 1000 == 700) chart.series[0].y[k] = -1;
  }
  chart.series[1].markers = true;
  chart.series[1].x.resize(20);
  chart.series[1].y.resize(20);
  for (size_t k = 0; k < 20; ++k) {
    chart.series[1].x[k] = 300.0 * k;
    chart.series[1].y[k] = k == 5 ? 0 : 0.5 * std::exp(-0.3 * k);
    chart.series[1].errors.push_back(0.6 * chart.series[1].y[k] + 0.001);
  }
  chart.references = {{0.01, "target 0.01"}, {-1, "not drawable"}};
  return chart;
}

}  // namespace
}  // namespace recon::report

int main(int argc, char** argv) {
  using namespace recon::report;
  const std::string dir = argc > 1 ? argv[1] : "/tmp";
  try {
    WriteChart(testing::PaperBarChart(), dir + "/recon_chart_bars.png");
    WriteChart(testing::PaperBarChart(), dir + "/recon_chart_bars.svg");
    WriteChart(LossCurves(), dir + "/recon_chart_loss.png");
    WriteChart(DataEfficiency(), dir + "/recon_chart_efficiency.png");
    WriteChart(ManyLongLabels(), dir + "/recon_chart_long_labels.png");
    WriteChart(ManyLongLabels(), dir + "/recon_chart_long_labels_small.png", 480, 300);
    WriteChart(NonPositiveLogY(), dir + "/recon_chart_log_nonpositive.png");
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 2;
  }
  std::printf("wrote %s/recon_chart_*.png\n", dir.c_str());
  return 0;
}
