// Training curves: smoothing and the choice of series for each chart.
#include "eval/training_curves.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace glint {

namespace {

// Colour-blind-friendly categorical palette: Okabe-Ito without its yellow (faint on white),
// grey for its black.
constexpr const char* kPalette[] = {"#0072b2", "#e69f00", "#009e73", "#cc79a7", "#56b4e9", "#d55e00", "#7f7f7f"};

ChartSeries series(const std::string& label, const std::vector<double>& x, std::vector<double> y, const char* color) {
  ChartSeries s;
  s.label = label;
  s.x = x;
  s.y = std::move(y);
  s.color = color;
  return s;
}

LineChart chart(const std::string& title, const std::string& yLabel, bool logY) {
  LineChart c;
  c.title = title;
  c.xLabel = "step";
  c.yLabel = yLabel;
  c.logY = logY;
  return c;
}

// The raw values (faint) and their running mean as two series; rawLabel is usually empty,
// so that the legend names each quantity once.
void addSmoothedSeries(LineChart& chart, const std::string& label, const std::string& rawLabel,
                       const std::vector<double>& steps, std::vector<double> values, const char* color,
                       double rawOpacity) {
  if (chart.logY)  // a log axis cannot show zeros; treat them as missing before averaging
    for (double& v : values)
      if (!(v > 0)) v = std::nan("");
  ChartSeries raw = series(rawLabel, steps, values, color);
  raw.opacity = rawOpacity;
  raw.strokeWidth = 0.8;
  chart.series.push_back(std::move(raw));  // faint, under the running mean that carries the legend entry
  chart.series.push_back(series(label, steps, runningMean(values, kSmoothingSteps), color));
}

bool anyPositive(const std::vector<double>& values) {
  return std::any_of(values.begin(), values.end(), [](double v) { return v > 0; });
}

}  // namespace

std::vector<double> runningMean(std::span<const double> values, int window) {
  const ptrdiff_t n = ptrdiff_t(values.size()), half = std::max(window, 1) / 2;
  // Prefix sums of the numbers and of how many there are, so each window costs O(1).
  std::vector<double> sum(size_t(n) + 1, 0.0);
  std::vector<ptrdiff_t> count(size_t(n) + 1, 0);
  for (ptrdiff_t i = 0; i < n; ++i) {
    bool number = std::isfinite(values[size_t(i)]);
    sum[size_t(i) + 1] = sum[size_t(i)] + (number ? values[size_t(i)] : 0.0);
    count[size_t(i) + 1] = count[size_t(i)] + (number ? 1 : 0);
  }
  std::vector<double> mean(static_cast<size_t>(n));
  for (ptrdiff_t i = 0; i < n; ++i) {
    size_t lo = size_t(std::max<ptrdiff_t>(0, i - half)), hi = size_t(std::min(n, i + half + 1));
    ptrdiff_t k = count[hi] - count[lo];
    mean[size_t(i)] = k > 0 ? (sum[hi] - sum[lo]) / double(k) : std::nan("");
  }
  return mean;
}

std::vector<LineChart> trainingCharts(const TrainingLog& log) {
  std::vector<LineChart> charts;
  if (!log.has("step") || log.rows() == 0) return charts;
  const std::vector<double>& steps = log.column("step");

  if (log.has("loss") && anyPositive(log.column("loss"))) {
    LineChart loss = chart("Total loss", "loss (log scale)", true);
    addSmoothedSeries(loss, "mean of " + std::to_string(kSmoothingSteps) + " steps", "per step", steps,
                      log.column("loss"), kPalette[0], 0.3);
    charts.push_back(std::move(loss));
  }

  LineChart terms = chart("L1 terms", "L1 (log scale)", true);
  size_t colour = 0;
  for (const std::string& name : log.names) {
    if (name.size() < 3 || name.compare(name.size() - 3, 3, "_l1") != 0 || !anyPositive(log.column(name))) continue;
    // Several noisy terms overlap: fainter raw values keep the means readable.
    addSmoothedSeries(terms, name, "", steps, log.column(name), kPalette[colour++ % std::size(kPalette)], 0.14);
  }
  if (!terms.series.empty()) charts.push_back(std::move(terms));

  if (log.has("gaussians")) {
    LineChart count = chart("Gaussians", "Gaussians", false);
    count.series.push_back(series("", steps, log.column("gaussians"), kPalette[2]));
    charts.push_back(std::move(count));
  }

  if (log.has("test_diffuse_psnr")) {
    // Only the rows that scored the test views.
    std::vector<double> x, y;
    const std::vector<double>& psnr = log.column("test_diffuse_psnr");
    for (size_t i = 0; i < psnr.size(); ++i)
      if (std::isfinite(psnr[i])) x.push_back(steps[i]), y.push_back(psnr[i]);
    if (!x.empty()) {
      LineChart test = chart("Test diffuse PSNR during training", "PSNR 8-bit (dB)", false);
      test.series.push_back(series("", x, y, kPalette[5]));
      test.series.back().markers = true;
      charts.push_back(std::move(test));
    }
  }
  return charts;
}

}  // namespace glint
