// SVG line charts: round axis ranges and ticks, exact data-to-pixel mapping on linear and
// log axes, gaps, thinning that keeps the extremes, escaping and well-formed markup.
#include "eval/svg_chart.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "eval/xml_check.h"

namespace glint {
namespace {

using Points = std::vector<std::pair<double, double>>;

// The points of every <polyline> in the SVG, one list per polyline. (Found with find, not
// std::regex, whose recursive matcher overflows the stack on long attributes.)
std::vector<Points> polylines(const std::string& svg) {
  std::vector<Points> lines;
  for (size_t at = svg.find("<polyline "); at != std::string::npos; at = svg.find("<polyline ", at + 1)) {
    size_t begin = svg.find("points=\"", at) + 8, end = svg.find('"', begin);
    Points points;
    std::istringstream in(svg.substr(begin, end - begin));
    double x, y;
    char comma;
    while (in >> x >> comma >> y) points.emplace_back(x, y);
    lines.push_back(points);
  }
  return lines;
}

LineChart oneSeries(std::vector<double> x, std::vector<double> y, bool logY) {
  LineChart chart;
  chart.title = "t";
  chart.logY = logY;
  ChartSeries s;
  s.x = std::move(x);
  s.y = std::move(y);
  chart.series.push_back(s);
  return chart;
}

TEST(SvgChartTest, LinearAxesWidenToRoundTicks) {
  ChartFrame f = chartFrame(oneSeries({1, 37, 100}, {3, 80, 41}, false));
  // 100 / 5 = 20 -> step 20 on x; 77 / 5 = 15.4 -> step 20 on y.
  EXPECT_DOUBLE_EQ(f.xMin, 0);
  EXPECT_DOUBLE_EQ(f.xMax, 100);
  EXPECT_DOUBLE_EQ(f.yMin, 0);
  EXPECT_DOUBLE_EQ(f.yMax, 80);
  EXPECT_EQ(axisTicks(0, 80, false), (std::vector<double>{0, 20, 40, 60, 80}));
  EXPECT_EQ(axisTicks(0, 8000, false), (std::vector<double>{0, 2000, 4000, 6000, 8000}));
  std::vector<double> small = axisTicks(-0.3, 0.3, false);
  ASSERT_EQ(small.size(), 7u);  // step 0.1
  EXPECT_NEAR(small[1], -0.2, 1e-12);
  EXPECT_EQ(small[3], 0.0);
  EXPECT_FALSE(std::signbit(small[3]));

  // A constant series still gets a range around it.
  ChartFrame flat = chartFrame(oneSeries({0, 10}, {5000, 5000}, false));
  EXPECT_LT(flat.yMin, 5000);
  EXPECT_GT(flat.yMax, 5000);
}

TEST(SvgChartTest, PointsLandWhereTheFrameSays) {
  LineChart chart = oneSeries({0, 50, 100}, {0, 40, 80}, false);
  ChartFrame f = chartFrame(chart);
  ASSERT_DOUBLE_EQ(f.xMax, 100);
  ASSERT_DOUBLE_EQ(f.yMax, 80);
  EXPECT_GT(f.right - f.left, 300);  // most of the 720 px width
  EXPECT_LT(f.left, 100);
  std::vector<Points> lines = polylines(renderSvgChart(chart));
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(lines[0].size(), 3u);
  // The ends of the data are the corners of the plot; the middle is its centre.
  EXPECT_NEAR(lines[0][0].first, f.left, 0.051);
  EXPECT_NEAR(lines[0][0].second, f.bottom, 0.051);
  EXPECT_NEAR(lines[0][1].first, (f.left + f.right) / 2, 0.051);
  EXPECT_NEAR(lines[0][1].second, (f.top + f.bottom) / 2, 0.051);
  EXPECT_NEAR(lines[0][2].first, f.right, 0.051);
  EXPECT_NEAR(lines[0][2].second, f.top, 0.051);
}

TEST(SvgChartTest, LogAxisSpacesDecadesEvenly) {
  LineChart chart = oneSeries({0, 1, 2, 3}, {1, 10, 100, 31.6227766}, true);
  ChartFrame f = chartFrame(chart);
  EXPECT_DOUBLE_EQ(f.yMin, 1);
  EXPECT_DOUBLE_EQ(f.yMax, 100);
  EXPECT_EQ(axisTicks(1, 100, true), (std::vector<double>{1, 10, 100}));
  std::vector<Points> lines = polylines(renderSvgChart(chart));
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(lines[0].size(), 4u);
  double height = f.bottom - f.top;
  EXPECT_NEAR(lines[0][0].second, f.bottom, 0.051);
  EXPECT_NEAR(lines[0][1].second, f.bottom - height / 2, 0.051);  // 10 is halfway from 1 to 100
  EXPECT_NEAR(lines[0][2].second, f.top, 0.051);
  EXPECT_NEAR(lines[0][3].second, f.bottom - height * 0.75, 0.051);  // 10^1.5

  // Less than a decade of data: the range rounds to 1, 2, 5 x 10^k and ticks add 2 and 5.
  ChartFrame narrow = chartFrame(oneSeries({0, 1}, {0.03, 0.4}, true));
  EXPECT_DOUBLE_EQ(narrow.yMin, 0.02);
  EXPECT_DOUBLE_EQ(narrow.yMax, 0.5);
  std::vector<double> ticks = axisTicks(0.02, 0.5, true);
  std::vector<double> expected = {0.02, 0.05, 0.1, 0.2, 0.5};
  ASSERT_EQ(ticks.size(), expected.size());
  for (size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-12);
}

TEST(SvgChartTest, MissingAndNonPositiveValuesAreGaps) {
  // On a log axis, 0 (e.g. a loss term before it starts) breaks the line like NaN does.
  LineChart chart = oneSeries({0, 1, 2, 3, 4, 5, 6}, {1, 2, 0, 4, 5, NAN, 7}, true);
  std::vector<Points> lines = polylines(renderSvgChart(chart));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].size(), 2u);
  EXPECT_EQ(lines[1].size(), 2u);
  EXPECT_EQ(lines[2].size(), 1u);
  ChartFrame f = chartFrame(chart);
  EXPECT_DOUBLE_EQ(f.yMin, 1);
  EXPECT_DOUBLE_EQ(f.yMax, 10);
}

TEST(SvgChartTest, LongSeriesAreThinnedButKeepTheirExtremes) {
  const int n = 100000;
  std::vector<double> x(n), y(n);
  for (int i = 0; i < n; ++i) x[i] = i, y[i] = 10 + std::sin(i * 0.37) * (1 + i % 7);
  y[54321] = 40;   // one spike up
  y[77777] = -25;  // and one down
  LineChart chart = oneSeries(x, y, false);
  ChartFrame f = chartFrame(chart);
  std::string svg = renderSvgChart(chart);
  std::vector<Points> lines = polylines(svg);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_LE(lines[0].size(), size_t(4 * (f.right - f.left + 2)));
  EXPECT_LT(svg.size(), 200000u);
  double top = 1e9, bottom = -1e9;
  for (auto [px, py] : lines[0]) top = std::min(top, py), bottom = std::max(bottom, py);
  EXPECT_NEAR(top, f.mapY(40), 0.051);
  EXPECT_NEAR(bottom, f.mapY(-25), 0.051);
  EXPECT_NEAR(lines[0].front().first, f.mapX(0), 0.051);
  EXPECT_NEAR(lines[0].back().first, f.mapX(n - 1), 0.051);
}

TEST(SvgChartTest, MarkupIsWellFormedWithEscapedText) {
  LineChart chart = oneSeries({0, 1, 2}, {1, 3, 2}, false);
  chart.title = "loss <total> & \"more\"";
  chart.xLabel = "step";
  chart.yLabel = "a'b";
  chart.series[0].label = "x<y";
  chart.series[0].markers = true;
  std::string svg = renderSvgChart(chart);
  EXPECT_EQ(test::markupProblem(svg), "");
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
  EXPECT_NE(svg.find("loss &lt;total&gt; &amp; &quot;more&quot;"), std::string::npos);
  EXPECT_NE(svg.find("x&lt;y"), std::string::npos);
  EXPECT_NE(svg.find("a&#39;b"), std::string::npos);
  EXPECT_EQ(svg.find("<total>"), std::string::npos);
  // Three markers, and tick labels on both axes.
  size_t circles = 0;
  for (size_t at = svg.find("<circle "); at != std::string::npos; at = svg.find("<circle ", at + 1)) ++circles;
  EXPECT_EQ(circles, 3u);
  EXPECT_NE(svg.find(">step</text>"), std::string::npos);
}

TEST(SvgChartTest, TickLabelsAreShort) {
  EXPECT_EQ(formatTick(0), "0");
  EXPECT_EQ(formatTick(0.001), "0.001");
  EXPECT_EQ(formatTick(2.5), "2.5");
  EXPECT_EQ(formatTick(8000), "8000");
  EXPECT_EQ(formatTick(250000), "250k");
  EXPECT_EQ(formatTick(1200000), "1.2M");
  EXPECT_EQ(formatTick(-40), "-40");
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A chart of one value (a run scored once) is that number, not a line through one point on
// an invented axis.
TEST(SvgChartTest, OnePointIsDrawnAsItsNumber) {
  LineChart chart;
  chart.title = "Test diffuse PSNR during training";
  chart.xLabel = "step";
  chart.yLabel = "PSNR 8-bit (dB)";
  ChartSeries s;
  s.x = {20};
  s.y = {27.5};
  chart.series.push_back(s);
  const std::string svg = renderSvgChart(chart);
  EXPECT_NE(svg.find("27.5"), std::string::npos) << svg;
  EXPECT_NE(svg.find("one value, at step 20"), std::string::npos) << svg;
  EXPECT_EQ(svg.find("<line"), std::string::npos) << "no axes for a single value";
  // Two points are a chart again.
  chart.series[0].x.push_back(40);
  chart.series[0].y.push_back(28.0);
  EXPECT_NE(renderSvgChart(chart).find("<line"), std::string::npos);
}

}  // namespace
}  // namespace glint
