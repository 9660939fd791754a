// SVG line charts: round axis ranges and ticks, data-to-pixel mapping, thinning of long
// series, and the markup.
#include "eval/svg_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

namespace glint {

namespace {

// Layout in SVG pixels: room for the title above the plot, tick labels and the x label
// below, tick labels and the rotated y label on the left, the legend on the right.
constexpr double kMarginLeft = 66;
constexpr double kMarginRight = 18;
constexpr double kMarginTop = 34;
constexpr double kMarginBottom = 44;
constexpr double kLegendCharWidth = 6.4;  // of the 11 px sans-serif legend text, roughly
constexpr double kLegendRow = 17;

bool validPoint(double x, double y, bool logY) { return std::isfinite(x) && std::isfinite(y) && (!logY || y > 0); }

// A round step (1, 2 or 5 x 10^k) that divides range into about five intervals.
double roundStep(double range) {
  double raw = range / 5.0;
  double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double f = raw / magnitude;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * magnitude;
}

// [lo, hi] widened to multiples of the round step; an empty range is opened up first.
void widenLinear(double& lo, double& hi) {
  if (!(hi > lo)) {
    double pad = lo == 0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad, hi += pad;
  }
  double step = roundStep(hi - lo);
  // The small tolerances keep a bound that already is a multiple from moving a step out.
  lo = std::floor(lo / step + 1e-9) * step;
  hi = std::ceil(hi / step - 1e-9) * step;
}

// [lo, hi] (both > 0) widened to 1, 2 or 5 x 10^k.
void widenLog(double& lo, double& hi) {
  if (!(hi > lo)) lo /= 2, hi *= 2;
  double decade = std::pow(10.0, std::floor(std::log10(lo)));
  double below = decade;
  for (double m : {2.0, 5.0, 10.0})
    if (m * decade <= lo * (1 + 1e-12)) below = m * decade;
  decade = std::pow(10.0, std::floor(std::log10(hi)));
  double above = 10 * decade;
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade >= hi * (1 - 1e-12)) above = m * decade;
  lo = below, hi = above;
}

// Pixel coordinates, to a tenth of a pixel.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

// Opacities and widths: "0.3", "1.6".
std::string shortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// Indices of the points of series s to draw, split into runs of valid points, each run
// thinned to first/lowest/highest/last per pixel column of the frame.
std::vector<std::vector<size_t>> drawnRuns(const ChartSeries& s, const ChartFrame& frame) {
  std::vector<std::vector<size_t>> runs;
  std::vector<size_t> run;
  size_t n = std::min(s.x.size(), s.y.size());
  size_t groupStart = 0;
  auto flushGroup = [&](size_t end) {  // points [groupStart, end) share one pixel column
    if (end == groupStart) return;
    size_t lowest = groupStart, highest = groupStart;
    for (size_t i = groupStart; i < end; ++i) {
      if (s.y[i] < s.y[lowest]) lowest = i;
      if (s.y[i] > s.y[highest]) highest = i;
    }
    size_t picks[] = {groupStart, std::min(lowest, highest), std::max(lowest, highest), end - 1};
    for (size_t p : picks)
      if (run.empty() || run.back() < p) run.push_back(p);
  };
  for (size_t i = 0; i <= n; ++i) {
    bool valid = i < n && validPoint(s.x[i], s.y[i], frame.logY);
    bool sameColumn = valid && i > groupStart &&
                      std::floor(frame.mapX(s.x[i])) == std::floor(frame.mapX(s.x[groupStart]));
    if (sameColumn) continue;
    flushGroup(i);
    if (!valid && !run.empty()) runs.push_back(std::move(run)), run.clear();
    groupStart = valid ? i : i + 1;
  }
  return runs;
}

}  // namespace

double ChartFrame::mapX(double x) const { return left + (x - xMin) / (xMax - xMin) * (right - left); }

double ChartFrame::mapY(double y) const {
  double t = logY ? (std::log10(y) - std::log10(yMin)) / (std::log10(yMax) - std::log10(yMin))
                  : (y - yMin) / (yMax - yMin);
  return bottom - t * (bottom - top);
}

ChartFrame chartFrame(const LineChart& chart) {
  ChartFrame f;
  f.logY = chart.logY;
  double xLo = std::numeric_limits<double>::infinity(), xHi = -xLo, yLo = xLo, yHi = -xLo;
  size_t legendChars = 0;
  for (const ChartSeries& s : chart.series) {
    legendChars = std::max(legendChars, s.label.size());
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!validPoint(s.x[i], s.y[i], chart.logY)) continue;
      xLo = std::min(xLo, s.x[i]), xHi = std::max(xHi, s.x[i]);
      yLo = std::min(yLo, s.y[i]), yHi = std::max(yHi, s.y[i]);
    }
  }
  if (!std::isfinite(xLo)) {  // nothing to draw: an empty frame over a unit range
    xLo = 0, xHi = 1;
    yLo = chart.logY ? 1 : 0, yHi = chart.logY ? 10 : 1;
  }
  widenLinear(xLo, xHi);
  chart.logY ? widenLog(yLo, yHi) : widenLinear(yLo, yHi);
  f.xMin = xLo, f.xMax = xHi, f.yMin = yLo, f.yMax = yHi;
  double legendWidth = legendChars > 0 ? 34 + kLegendCharWidth * double(legendChars) : 0;
  f.left = kMarginLeft;
  f.top = kMarginTop;
  f.right = std::max(f.left + 10, double(chart.width) - kMarginRight - legendWidth);
  f.bottom = std::max(f.top + 10, double(chart.height) - kMarginBottom);
  return f;
}

std::vector<double> axisTicks(double lo, double hi, bool logScale) {
  std::vector<double> ticks;
  if (!(hi > lo)) return ticks;
  if (!logScale) {
    double step = roundStep(hi - lo);
    for (double k = std::ceil(lo / step - 1e-9); k <= std::floor(hi / step + 1e-9); ++k)
      ticks.push_back(k * step + 0.0);  // + 0.0 turns -0 into 0
    return ticks;
  }
  if (!(lo > 0)) return ticks;
  auto inside = [&](double v) { return v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9); };
  int first = int(std::floor(std::log10(lo))), last = int(std::ceil(std::log10(hi)));
  for (int k = first; k <= last; ++k)
    if (inside(std::pow(10.0, k))) ticks.push_back(std::pow(10.0, k));
  if (ticks.size() < 3) {
    for (int k = first; k <= last; ++k)
      for (double m : {2.0, 5.0})
        if (inside(m * std::pow(10.0, k))) ticks.push_back(m * std::pow(10.0, k));
    std::sort(ticks.begin(), ticks.end());
  }
  return ticks;
}

std::string formatTick(double value) {
  char text[32];
  double a = std::abs(value);
  if (a >= 1e6)
    std::snprintf(text, sizeof text, "%.3gM", value / 1e6);
  else if (a >= 1e4)
    std::snprintf(text, sizeof text, "%.3gk", value / 1e3);
  else
    std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

// The one finite point of a chart's series, when the chart has no more than one: a line
// through a single point says nothing, and its axis would span a made-up range.
std::optional<std::pair<double, double>> onlyPoint(const LineChart& chart) {
  std::optional<std::pair<double, double>> point;
  for (const ChartSeries& s : chart.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if (point && (point->first != s.x[i] || point->second != s.y[i])) return std::nullopt;
      point = std::make_pair(s.x[i], s.y[i]);
    }
  return point;
}

}  // namespace

std::string renderSvgChart(const LineChart& chart) {
  if (std::optional<std::pair<double, double>> point = onlyPoint(chart)) {
    // One value: the number, not a chart.
    const std::string w = std::to_string(chart.width);
    return "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" viewBox=\"0 0 " + w + " 48\" width=\"" + w +
           "\" height=\"48\" role=\"img\" aria-label=\"" + escapeXml(chart.title) +
           "\" font-family=\"system-ui, sans-serif\" font-size=\"13\">\n<rect width=\"" + w +
           "\" height=\"48\" fill=\"#ffffff\"/>\n<text x=\"8\" y=\"28\" fill=\"#222\"><tspan font-weight=\"600\">" +
           escapeXml(chart.title) + ":</tspan> " + escapeXml(formatTick(point->second)) + " (" +
           escapeXml(chart.yLabel) + ", one value, at " + escapeXml(chart.xLabel.empty() ? "x" : chart.xLabel) + " " +
           escapeXml(formatTick(point->first)) + ")</text>\n</svg>\n";
  }
  ChartFrame f = chartFrame(chart);
  const std::string w = std::to_string(chart.width), h = std::to_string(chart.height);
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" viewBox=\"0 0 " + w + " " + h +
                    "\" width=\"" + w + "\" height=\"" + h + "\" role=\"img\" aria-label=\"" +
                    escapeXml(chart.title) + "\" font-family=\"system-ui, sans-serif\" font-size=\"11\">\n";
  svg += "<rect width=\"" + w + "\" height=\"" + h + "\" fill=\"#ffffff\"/>\n";
  svg += "<text x=\"" + number(f.left) + "\" y=\"20\" font-size=\"13\" font-weight=\"600\" fill=\"#222\">" +
         escapeXml(chart.title) + "</text>\n";

  // Grid lines and tick labels.
  for (double t : axisTicks(f.yMin, f.yMax, f.logY)) {
    std::string y = number(f.mapY(t));
    svg += "<line x1=\"" + number(f.left) + "\" x2=\"" + number(f.right) + "\" y1=\"" + y + "\" y2=\"" + y +
           "\" stroke=\"#e6e6e6\"/>\n";
    svg += "<text x=\"" + number(f.left - 6) + "\" y=\"" + number(f.mapY(t) + 4) +
           "\" text-anchor=\"end\" fill=\"#555\">" + escapeXml(formatTick(t)) + "</text>\n";
  }
  for (double t : axisTicks(f.xMin, f.xMax, false)) {
    std::string x = number(f.mapX(t));
    svg += "<line x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" + number(f.top) + "\" y2=\"" + number(f.bottom) +
           "\" stroke=\"#e6e6e6\"/>\n";
    svg += "<text x=\"" + x + "\" y=\"" + number(f.bottom + 16) + "\" text-anchor=\"middle\" fill=\"#555\">" +
           escapeXml(formatTick(t)) + "</text>\n";
  }
  svg += "<rect x=\"" + number(f.left) + "\" y=\"" + number(f.top) + "\" width=\"" + number(f.right - f.left) +
         "\" height=\"" + number(f.bottom - f.top) + "\" fill=\"none\" stroke=\"#999\"/>\n";
  svg += "<text x=\"" + number((f.left + f.right) / 2) + "\" y=\"" + number(double(chart.height) - 8) +
         "\" text-anchor=\"middle\" fill=\"#333\">" + escapeXml(chart.xLabel) + "</text>\n";
  svg += "<text transform=\"translate(16," + number((f.top + f.bottom) / 2) +
         ") rotate(-90)\" text-anchor=\"middle\" fill=\"#333\">" + escapeXml(chart.yLabel) + "</text>\n";

  // The data: the ranges contain every valid point, so nothing needs clipping.
  for (const ChartSeries& s : chart.series) {
    std::string style = "fill=\"none\" stroke=\"" + escapeXml(s.color) + "\" stroke-opacity=\"" +
                        shortNumber(s.opacity) + "\" stroke-width=\"" + shortNumber(s.strokeWidth) +
                        "\" stroke-linejoin=\"round\" stroke-linecap=\"round\"";
    for (const std::vector<size_t>& run : drawnRuns(s, f)) {
      std::string points;
      for (size_t i : run) {
        if (!points.empty()) points += ' ';
        points += number(f.mapX(s.x[i]));
        points += ',';
        points += number(f.mapY(s.y[i]));
      }
      svg += "<polyline " + style + " points=\"" + points + "\"/>\n";
    }
    if (s.markers)
      for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (validPoint(s.x[i], s.y[i], f.logY))
          svg += "<circle cx=\"" + number(f.mapX(s.x[i])) + "\" cy=\"" + number(f.mapY(s.y[i])) +
                 "\" r=\"2.6\" fill=\"" + escapeXml(s.color) + "\" fill-opacity=\"" + shortNumber(s.opacity) +
                 "\"/>\n";
  }

  // Legend, to the right of the plot.
  double row = f.top + 8;
  for (const ChartSeries& s : chart.series) {
    if (s.label.empty()) continue;
    std::string y = number(row);
    svg += "<line x1=\"" + number(f.right + 12) + "\" x2=\"" + number(f.right + 32) + "\" y1=\"" + y + "\" y2=\"" +
           y + "\" stroke=\"" + escapeXml(s.color) + "\" stroke-opacity=\"" + shortNumber(s.opacity) +
           "\" stroke-width=\"2.5\"/>\n";
    svg += "<text x=\"" + number(f.right + 38) + "\" y=\"" + number(row + 4) + "\" fill=\"#333\">" +
           escapeXml(s.label) + "</text>\n";
    row += kLegendRow;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace glint
