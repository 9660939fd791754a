// The report page: a section per view, escaped text, images as data: URIs whose PNGs hold
// the tonemapped pixels, error maps and G-buffers, the edit-consistency table and the
// configuration, well-formed markup, no reference to anything outside the page.
#include "eval/html_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/base64_decode.h"
#include "eval/xml_check.h"
#include "io/temp_folder.h"
#include "io/tonemap.h"

namespace glint {
namespace {

int countOf(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A 4x3 image whose pixel (x, y) is radiance (0.1 x + seed, 0.3 y, 2 seed): values above
// 1 too, which the tonemap compresses.
Image ramp(float seed) {
  Image image(4, 3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) image.setRgb(x, y, {0.1f * float(x) + seed, 0.3f * float(y), 2 * seed});
  return image;
}

HtmlReportContent sampleContent(int views) {
  HtmlReportContent c;
  c.title = "Glint report: run <1> & co";
  c.facts = {{"dataset", "D \"quoted\""}, {"steps", "8000"}};
  c.mean.diffuse = {33.456, 0.95, 31.2, 0.9};
  c.mean.specular.psnr = std::numeric_limits<double>::quiet_NaN();
  c.mean.final.psnr = std::numeric_limits<double>::infinity();
  c.mean.depthRmse = 0.01234;
  for (int v = 0; v < views; ++v) {
    std::string name = "test/render/render_000" + std::to_string(v);
    c.perView.emplace_back(name, c.mean);
    ReportView view{name, {}, {}};
    for (const char* pass : {"diffuse", "specular", "final"})
      view.passes.push_back({pass, ramp(0.5f * float(v)), ramp(0.5f * float(v) + 0.05f), c.mean.diffuse});
    for (const char* g : {"normal", "depth", "roughness", "f0"})
      view.gBuffers.push_back({g, {Image(4, 3, 3, 0.25f), Image(4, 3, 3, 0.75f), "scale <of> " + std::string(g)}});
    c.views.push_back(view);
  }
  LineChart chart;
  chart.title = "Total loss";
  chart.series.push_back({"loss", {1, 2, 3}, {0.5, 0.4, 0.3}});
  c.charts.push_back(chart);
  c.note = "made by <glint>";
  return c;
}

TEST(HtmlReportTest, HasASectionPerViewAndEscapesText) {
  std::string html = renderHtmlReport(sampleContent(3));
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(test::markupProblem(html, true), "");
  EXPECT_EQ(countOf(html, "<section class=\"view\">"), 3);
  // Ground truth, ours and error map of three passes, ground truth and ours of four G-buffers.
  EXPECT_EQ(countOf(html, "<img "), 3 * (9 + 8));
  EXPECT_NE(html.find("scale &lt;of&gt; depth"), std::string::npos);
  EXPECT_NE(html.find("LPIPS is not reported"), std::string::npos);
  EXPECT_EQ(html.find("Edit consistency"), std::string::npos);  // no edited evaluation
  EXPECT_EQ(html.find("Training configuration"), std::string::npos);  // none given
  for (int v = 0; v < 3; ++v) EXPECT_NE(html.find("<h3>test/render/render_000" + std::to_string(v)), std::string::npos);
  // Per-view table: three rows and the mean.
  EXPECT_EQ(countOf(html, "<td>test/render/render_000"), 3);
  EXPECT_EQ(countOf(html, "<tr class=\"mean\">"), 1);
  EXPECT_NE(html.find("Glint report: run &lt;1&gt; &amp; co"), std::string::npos);
  EXPECT_NE(html.find("D &quot;quoted&quot;"), std::string::npos);
  EXPECT_NE(html.find("made by &lt;glint&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<glint>"), std::string::npos);
  EXPECT_EQ(html.find("run <1>"), std::string::npos);
  // Metrics: rounded, NaN as "-", infinity as "inf".
  EXPECT_NE(html.find("<td>33.46</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>0.0123</td>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>specular</td><td>-</td>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>final</td><td>inf</td>"), std::string::npos);
  EXPECT_NE(html.find("ours <b>31.20 dB</b>"), std::string::npos);
  EXPECT_EQ(countOf(html, "<svg "), 1);
  // Self-contained: nothing is fetched.
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("url("), std::string::npos);

  std::string noViews = renderHtmlReport(sampleContent(0));
  EXPECT_EQ(countOf(noViews, "<section class=\"view\">"), 0);
  EXPECT_EQ(test::markupProblem(noViews, true), "");
}

TEST(HtmlReportTest, ImagesAreTonemappedPngDataUris) {
  std::string html = renderHtmlReport(sampleContent(2));
  const std::string prefix = "src=\"data:image/png;base64,";
  std::vector<std::string> payloads;
  for (size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1)) {
    size_t begin = at + prefix.size();
    payloads.push_back(html.substr(begin, html.find('"', begin) - begin));
  }
  constexpr size_t kPerView = 3 * 3 + 4 * 2;
  ASSERT_EQ(payloads.size(), 2 * kPerView);
  test::TempFolder folder;
  for (size_t i = 0; i < payloads.size(); ++i) {
    std::optional<std::string> png = test::decodeBase64(payloads[i]);
    ASSERT_TRUE(png.has_value()) << i;
    ASSERT_EQ(png->substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << i;
    // Decode the PNG and compare with what it shows: per view, ground truth, ours and the
    // error map of each pass, then ground truth (0.25) and ours (0.75) of each G-buffer.
    test::writeBytes(folder / "shown.png", *png);
    Image shown = readImage(folder / "shown.png");
    ASSERT_EQ(shown.width, 4);
    ASSERT_EQ(shown.height, 3);
    size_t view = i / kPerView, k = i % kPerView;
    Image truth = ramp(0.5f * float(view)), ours = ramp(0.5f * float(view) + 0.05f);
    Image expected;
    if (k >= 9) {
      expected = Image(4, 3, 3, (k - 9) % 2 == 0 ? 0.25f : 0.75f);
    } else if (k % 3 == 2) {
      expected = errorMap(truth, ours);
    } else {
      expected = k % 3 == 0 ? truth : ours;
      for (float& value : expected.pixels) value = tonemapFilmic(value);
    }
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x)
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(shown.at(x, y, ch), expected.at(x, y, ch), 0.5f / 255 + 1e-6f) << i;
  }
}

TEST(HtmlReportTest, EditedEvaluationsGetTheirDropFromTheUneditedOne) {
  HtmlReportContent c = sampleContent(1);
  c.evaluationLabel = "metrics.json: 64 spp";
  c.mean.final.psnrTonemapped = 30.0;
  OtherEvaluation moved{"moved.json: 64 spp, edits move.json", c.mean, "move.json"};
  moved.mean.final.psnrTonemapped = 28.75;
  moved.mean.diffuse.psnrTonemapped = 31.2 - 2.5;
  c.otherEvaluations = {{"more.json: 128 spp", c.mean, ""}, moved};
  std::string html = renderHtmlReport(c);
  EXPECT_EQ(test::markupProblem(html, true), "");
  size_t table = html.find("<h2>Edit consistency</h2>");
  ASSERT_NE(table, std::string::npos);
  // The page's own evaluation is the unedited reference, not the other unedited one.
  EXPECT_NE(html.find("<td>none (metrics.json: 64 spp (this page))</td>", table), std::string::npos);
  size_t row = html.find("<tr><td>move.json</td>", table);
  ASSERT_NE(row, std::string::npos);
  std::string cells = html.substr(row, html.find("</tr>", row) - row);
  EXPECT_NE(cells.find("<td>28.70</td><td>2.50 dB</td>"), std::string::npos) << cells;  // diffuse
  EXPECT_NE(cells.find("<td>28.75</td><td>1.25 dB</td>"), std::string::npos) << cells;  // final

  // Without an unedited evaluation there is nothing to compare with.
  c.evaluationEdits = "move.json";
  c.otherEvaluations = {moved};
  EXPECT_EQ(renderHtmlReport(c).find("Edit consistency"), std::string::npos);
}

TEST(HtmlReportTest, ConfigurationIsShownWholeAndEscaped) {
  HtmlReportContent c = sampleContent(0);
  c.configSource = "R/config.json";
  c.configText = "{\n  \"dataset\": \"<D>\",\n  \"iters\": 8000\n}";
  std::string html = renderHtmlReport(c);
  EXPECT_EQ(test::markupProblem(html, true), "");
  EXPECT_NE(html.find("<summary>R/config.json</summary>"), std::string::npos);
  EXPECT_NE(html.find("&quot;dataset&quot;: &quot;&lt;D&gt;&quot;,\n  &quot;iters&quot;: 8000"), std::string::npos);
}

}  // namespace
}  // namespace glint
