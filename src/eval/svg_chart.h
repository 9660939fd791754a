// Line charts as inline SVG (axes with ticks and labels, grid, legend), for pages that
// must not load anything: the training curves of `glint report`.
#pragma once

#include <string>
#include <vector>

namespace glint {

// One line of a chart. Points whose y is not finite (or not positive on a log axis) are
// gaps: the line stops there and starts again at the next valid point.
struct ChartSeries {
  std::string label;  // legend entry; empty = not in the legend
  std::vector<double> x;
  std::vector<double> y;
  std::string color = "#1f77b4";
  double opacity = 1.0;
  double strokeWidth = 1.6;
  bool markers = false;  // a dot at each valid point (for sparse data)
};

struct LineChart {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  bool logY = false;
  int width = 720;   // SVG size in pixels
  int height = 300;
  std::vector<ChartSeries> series;
};

// Where the plot area lies in the SVG and which values its edges stand for: x and y
// ranges are the data ranges widened to round tick values (1, 2 or 5 x 10^k; on a log
// axis the same mantissas), so the outermost ticks sit on the frame.
struct ChartFrame {
  double left = 0, top = 0, right = 0, bottom = 0;  // plot area, SVG pixels (y grows down)
  double xMin = 0, xMax = 1, yMin = 0, yMax = 1;    // yMin > 0 on a log axis
  bool logY = false;

  double mapX(double x) const;  // data -> SVG pixel
  double mapY(double y) const;
};

ChartFrame chartFrame(const LineChart& chart);

// Tick values within [lo, hi]: multiples of a round step (about five of them) on a
// linear axis; powers of ten on a log axis, with 2 and 5 x 10^k added when fewer than
// three powers fall inside.
std::vector<double> axisTicks(double lo, double hi, bool logScale);

// Short tick label: "0.001", "2.5", "40", "8000", "250k", "1.2M".
std::string formatTick(double value);

// A standalone <svg> element (no XML prolog), text escaped. Long series are thinned to at
// most four points per horizontal pixel (first, lowest, highest, last), which draws the
// same picture as every point. A chart of a single point is drawn as its number.
std::string renderSvgChart(const LineChart& chart);

// Escapes &, <, >, " and ' for text and attribute values of HTML and SVG.
std::string escapeXml(const std::string& text);

}  // namespace glint
