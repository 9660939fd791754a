// Markup of the report page: header facts, metric tables, images per view, charts, config.
#include "eval/html_report.h"

#include <algorithm>

#include "io/base64.h"
#include "io/tonemap.h"

namespace glint {

namespace {

constexpr const char* kStyle = R"(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; color: #222; background: #f6f6f4;
       max-width: 1280px; margin: 24px auto; padding: 0 20px; }
h1 { font-size: 22px; margin: 0 0 10px; }
h2 { font-size: 17px; margin: 30px 0 10px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
h3 { font-size: 13px; margin: 0 0 6px; font-weight: 600; color: #444; }
.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 16px; margin: 0; }
.facts dt { color: #666; } .facts dd { margin: 0; font-variant-numeric: tabular-nums; }
table { border-collapse: collapse; background: #fff; font-variant-numeric: tabular-nums; }
th, td { padding: 4px 10px; text-align: right; border-bottom: 1px solid #eee; }
th { background: #eceae4; font-weight: 600; } th.group { text-align: center; }
td:first-child, th:first-child { text-align: left; }
tr.mean td { font-weight: 600; border-top: 2px solid #ccc; }
.scroll { overflow-x: auto; }
.hint { color: #666; font-size: 12.5px; }
.view { background: #fff; padding: 10px 12px 12px; margin: 0 0 12px; border-radius: 6px; }
.passes { display: grid; grid-template-columns: repeat(3, minmax(0, 1fr)); gap: 16px; }
.pass-name { font-size: 12px; color: #555; text-transform: uppercase; letter-spacing: .05em; margin-bottom: 3px; }
.pair { display: grid; grid-template-columns: 1fr 1fr; gap: 4px; }
.triple { display: grid; grid-template-columns: repeat(3, 1fr); gap: 4px; }
.gbuffers { display: grid; grid-template-columns: repeat(4, minmax(0, 1fr)); gap: 16px; margin-top: 10px; }
.ramp { display: inline-block; width: 160px; height: 10px; vertical-align: middle; border-radius: 2px;
        background: linear-gradient(to right, #000, #470f73, #bf3361, #fa8c1a, #fcf7b3); }
pre.config { background: #fff; padding: 10px 12px; border-radius: 6px; overflow-x: auto; font-size: 12.5px; }
details summary { cursor: pointer; color: #444; }
figure { margin: 0; }
figure img { display: block; width: 100%; height: auto; image-rendering: pixelated; background: #000; }
figcaption { font-size: 12px; color: #444; margin-top: 2px; font-variant-numeric: tabular-nums; }
.charts { display: grid; grid-template-columns: repeat(auto-fit, minmax(520px, 1fr)); gap: 14px; }
.chart { display: block; width: 100%; height: auto; border-radius: 6px; }
footer { margin: 30px 0 10px; color: #777; font-size: 12px; }
)";

std::string cell(const std::string& text) { return "<td>" + escapeXml(text) + "</td>"; }

std::string meanTable(const ViewMetrics& mean) {
  std::string html =
      "<table><thead><tr><th>pass</th><th>PSNR (dB)</th><th>SSIM</th><th>PSNR 8-bit (dB)</th><th>SSIM 8-bit</th>"
      "</tr></thead><tbody>\n";
  auto row = [&](const char* name, const PassMetrics& p) {
    html += "<tr>" + cell(name) + cell(formatMetric(p.psnr, 2)) + cell(formatMetric(p.ssim, 4)) +
            cell(formatMetric(p.psnrTonemapped, 2)) + cell(formatMetric(p.ssimTonemapped, 4)) + "</tr>\n";
  };
  row("diffuse", mean.diffuse);
  row("specular", mean.specular);
  row("final", mean.final);
  html += "</tbody></table>\n<p>Depth RMSE <b>" + escapeXml(formatMetric(mean.depthRmse, 4)) +
          "</b> &middot; mean normal angle <b>" + escapeXml(formatMetric(mean.normalAngleDegrees, 2)) +
          "&deg;</b></p>\n";
  return html;
}

// One row per evaluation of the run, the page's own first: the 8-bit PSNR and SSIM of
// every pass, so that settings (spp, bounces, denoising) compare at a glance.
std::string evaluationsTable(const HtmlReportContent& c) {
  std::string html = "<table><thead><tr><th>evaluation</th>";
  for (const char* pass : {"diffuse", "specular", "final"})
    html += std::string("<th>") + pass + " PSNR 8-bit</th><th>" + pass + " SSIM 8-bit</th>";
  html += "</tr></thead><tbody>\n";
  auto row = [&](const std::string& label, const ViewMetrics& m) {
    html += "<tr>" + cell(label);
    for (const PassMetrics* p : {&m.diffuse, &m.specular, &m.final})
      html += cell(formatMetric(p->psnrTonemapped, 2)) + cell(formatMetric(p->ssimTonemapped, 4));
    html += "</tr>\n";
  };
  row(c.evaluationLabel + " (this page)", c.mean);
  for (const OtherEvaluation& e : c.otherEvaluations) row(e.label, e.mean);
  return html + "</tbody></table>\n";
}

std::string passCells(const PassMetrics& p) {
  return cell(formatMetric(p.psnr, 2)) + cell(formatMetric(p.psnrTonemapped, 2)) +
         cell(formatMetric(p.ssimTonemapped, 4));
}

std::string perViewTable(const std::vector<std::pair<std::string, ViewMetrics>>& views, const ViewMetrics& mean) {
  std::string html =
      "<div class=\"scroll\"><table><thead><tr><th rowspan=\"2\">view</th><th class=\"group\" colspan=\"3\">diffuse</th>"
      "<th class=\"group\" colspan=\"3\">specular</th><th class=\"group\" colspan=\"3\">final</th>"
      "<th rowspan=\"2\">depth RMSE</th><th rowspan=\"2\">normal (&deg;)</th></tr><tr>";
  for (int pass = 0; pass < 3; ++pass) html += "<th>PSNR</th><th>8-bit</th><th>SSIM 8-bit</th>";
  html += "</tr></thead><tbody>\n";
  auto row = [&](const std::string& name, const ViewMetrics& m, const char* rowClass) {
    html += std::string("<tr") + rowClass + ">" + cell(name) + passCells(m.diffuse) + passCells(m.specular) +
            passCells(m.final) + cell(formatMetric(m.depthRmse, 4)) + cell(formatMetric(m.normalAngleDegrees, 2)) +
            "</tr>\n";
  };
  for (const auto& [name, metrics] : views) row(name, metrics, "");
  row("mean", mean, " class=\"mean\"");
  html += "</tbody></table></div>\n";
  return html;
}

std::string figureOf(const std::string& dataUri, const Image& image, const std::string& alt,
                     const std::string& caption) {
  return "<figure><img src=\"" + dataUri + "\" width=\"" + std::to_string(image.width) + "\" height=\"" +
         std::to_string(image.height) + "\" alt=\"" + escapeXml(alt) + "\"><figcaption>" + caption +
         "</figcaption></figure>";
}

// A figure of linear radiance, tonemapped.
std::string figure(const Image& linear, const std::string& alt, const std::string& caption) {
  return figureOf(tonemappedPngDataUri(linear), linear, alt, caption);
}

// A figure of an image already in display values (error maps, G-buffers).
std::string displayFigure(const Image& shown, const std::string& alt, const std::string& caption) {
  return figureOf(displayPngDataUri(shown), shown, alt, caption);
}

std::string viewSection(const ReportView& view) {
  std::string html = "<section class=\"view\"><h3>" + escapeXml(view.name) + "</h3><div class=\"passes\">\n";
  for (const ReportPass& p : view.passes) {
    std::string caption = "ours <b>" + escapeXml(formatMetric(p.metrics.psnrTonemapped, 2)) +
                          " dB</b> &middot; linear " + escapeXml(formatMetric(p.metrics.psnr, 2));
    html += "<div><div class=\"pass-name\">" + escapeXml(p.name) + "</div><div class=\"triple\">" +
            figure(p.truth, view.name + " " + p.name + " ground truth", "ground truth") +
            figure(p.ours, view.name + " " + p.name + " ours", caption) +
            displayFigure(errorMap(p.truth, p.ours), view.name + " " + p.name + " error map", "error") +
            "</div></div>\n";
  }
  html += "</div>\n";
  if (!view.gBuffers.empty()) {
    html += "<div class=\"gbuffers\">\n";
    for (const ReportGBuffer& g : view.gBuffers)
      html += "<div><div class=\"pass-name\">" + escapeXml(g.name) + "</div><div class=\"pair\">" +
              displayFigure(g.pictures.truth, view.name + " " + g.name + " ground truth", "ground truth") +
              displayFigure(g.pictures.ours, view.name + " " + g.name + " ours", "ours") +
              "</div><div class=\"hint\">" + escapeXml(g.pictures.scale) + "</div></div>\n";
    html += "</div>\n";
  }
  html += "</section>\n";
  return html;
}

// Edited evaluations (`glint eval --edits` against the edited scene's own ground truth)
// against the run's unedited one: how much of each pass an edit costs. Empty when the run
// has no edited evaluation or no unedited one to compare with.
std::string editConsistencyTable(const HtmlReportContent& c) {
  std::vector<OtherEvaluation> all = c.otherEvaluations;
  all.insert(all.begin(), {c.evaluationLabel + " (this page)", c.mean, c.evaluationEdits});
  const OtherEvaluation* unedited = nullptr;
  for (const OtherEvaluation& e : all)
    if (e.edits.empty()) {
      unedited = &e;
      break;
    }
  bool anyEdited = std::any_of(all.begin(), all.end(), [](const OtherEvaluation& e) { return !e.edits.empty(); });
  if (!unedited || !anyEdited) return "";
  std::string html = "<table><thead><tr><th>edit file</th>";
  for (const char* pass : {"diffuse", "specular", "final"})
    html += std::string("<th>") + pass + " PSNR 8-bit</th><th>" + pass + " drop</th>";
  html += "</tr></thead><tbody>\n<tr>" + cell("none (" + unedited->label + ")");
  for (const PassMetrics* p : {&unedited->mean.diffuse, &unedited->mean.specular, &unedited->mean.final})
    html += cell(formatMetric(p->psnrTonemapped, 2)) + cell("-");
  html += "</tr>\n";
  for (const OtherEvaluation& e : all) {
    if (e.edits.empty()) continue;
    html += "<tr>" + cell(e.edits);
    const PassMetrics* before[] = {&unedited->mean.diffuse, &unedited->mean.specular, &unedited->mean.final};
    const PassMetrics* after[] = {&e.mean.diffuse, &e.mean.specular, &e.mean.final};
    for (int k = 0; k < 3; ++k)
      html += cell(formatMetric(after[k]->psnrTonemapped, 2)) +
              cell(formatMetric(before[k]->psnrTonemapped - after[k]->psnrTonemapped, 2) + " dB");
    html += "</tr>\n";
  }
  return html + "</tbody></table>\n";
}

}  // namespace

std::string tonemappedPngDataUri(const Image& linear) {
  Image shown(linear.width, linear.height, 3);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) shown.setRgb(x, y, tonemapFilmic(linear.rgb(x, y)));
  return displayPngDataUri(shown);
}

std::string displayPngDataUri(const Image& shown) { return "data:image/png;base64," + encodeBase64(encodePng(shown)); }

std::string renderHtmlReport(const HtmlReportContent& c) {
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
                     escapeXml(c.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  html += "<header><h1>" + escapeXml(c.title) + "</h1>\n<dl class=\"facts\">\n";
  for (const auto& [label, value] : c.facts) html += "<dt>" + escapeXml(label) + "</dt><dd>" + escapeXml(value) + "</dd>\n";
  html += "</dl></header>\n";

  html += "<section><h2>Metrics (mean over " + std::to_string(c.perView.size()) + " views)</h2>\n" + meanTable(c.mean);
  const std::string transfer = c.displayTransfer == "filmic"
                                   ? "the filmic tonemap (the paper's, for Glint's linear datasets)"
                                   : "the dataset's own " + c.displayTransfer +
                                         " transfer (its images are display-referred; published figures use it)";
  html += "<p class=\"hint\">PSNR and SSIM in linear space (data range 1) and on 8-bit images made with " +
          escapeXml(transfer) +
          ". Pictures below use the filmic tonemap. A linear PSNR can be negative: radiance is not bounded by 1 "
          "(highlights and light sources in the ground truth go above it), so the mean squared error with data "
          "range 1 can exceed 1; the 8-bit figures cannot. SSIM: 11x11 Gaussian window, sigma 1.5. Depth and "
          "normals where the ground truth has a surface. LPIPS is not reported: it needs the trained weights of a "
          "neural network, which Glint neither ships nor downloads.</p>\n</section>\n";
  if (!c.otherEvaluations.empty())
    html += "<section><h2>All evaluations of this run</h2>\n" + evaluationsTable(c) +
            "<p class=\"hint\">Every metrics file of <code>glint eval</code> in the run's eval folder, on the same "
            "views.</p>\n</section>\n";
  if (std::string edits = editConsistencyTable(c); !edits.empty())
    html += "<section><h2>Edit consistency</h2>\n" + edits +
            "<p class=\"hint\">Each edited evaluation is scored against the edited scene's own ground truth "
            "(<code>glint synth --edits</code>, then <code>glint eval --edits</code>); the drop is the unedited "
            "evaluation's 8-bit PSNR minus the edited one's.</p>\n</section>\n";
  html += "<section><h2>Per view</h2>\n" + perViewTable(c.perView, c.mean) + "</section>\n";

  if (!c.views.empty()) {
    html += "<section><h2>Views: ground truth and ours</h2>\n<p class=\"hint\">Filmic tonemap (the same as the 8-bit "
            "metrics). Under each of ours: the view's PSNR on the 8-bit images, then in linear space. Error maps: "
            "the largest channel difference of the 8-bit images per pixel, <span class=\"ramp\"></span> from 0 to "
            "64 levels of 255 or more. Below, the G-buffers the evaluation rendered beside the ground truth's.</p>\n";
    for (const ReportView& v : c.views) html += viewSection(v);
    html += "</section>\n";
  }
  if (!c.charts.empty()) {
    html += "<section><h2>Training curves</h2>\n<div class=\"charts\">\n";
    for (const LineChart& chart : c.charts) html += renderSvgChart(chart);
    html += "</div>\n";
    if (!c.chartNote.empty()) html += "<p class=\"hint\">" + escapeXml(c.chartNote) + "</p>\n";
    html += "</section>\n";
  }
  if (!c.configText.empty())
    html += "<section><h2>Training configuration</h2>\n<details><summary>" + escapeXml(c.configSource) +
            "</summary>\n<pre class=\"config\">" + escapeXml(c.configText) + "</pre></details>\n</section>\n";
  if (!c.note.empty()) html += "<footer>" + escapeXml(c.note) + "</footer>\n";
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace glint
