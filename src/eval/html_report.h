// The page of `glint report`: one self-contained HTML file (images as data: URIs of PNGs,
// charts as inline SVG, inline CSS) with a run's metrics, test views with their error maps
// and G-buffers, edit consistency, the training configuration and curves.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "eval/report_images.h"
#include "eval/svg_chart.h"
#include "eval/view_metrics.h"
#include "io/image.h"

namespace glint {

// One radiance pass of one view: ground truth and ours, both linear (shown through the
// filmic tonemap of io/tonemap.h, as the 8-bit metrics see them).
struct ReportPass {
  std::string name;  // "diffuse", "specular", "final"
  Image truth;
  Image ours;
  PassMetrics metrics;
};

// One G-buffer of one view, as display images (eval/report_images.h).
struct ReportGBuffer {
  std::string name;  // "normal", "depth", "roughness", "f0"
  GBufferPictures pictures;
};

struct ReportView {
  std::string name;  // the view's file_path
  std::vector<ReportPass> passes;       // each shown as ground truth, ours and their error map
  std::vector<ReportGBuffer> gBuffers;  // ground truth and ours
};

// The means of another evaluation of the same run (e.g. `glint eval RUN --spp 128
// --denoise specular -o RUN/eval/other.json`), shown as one row of a comparison table.
struct OtherEvaluation {
  std::string label;  // what was evaluated: file, spp, bounces, denoising
  ViewMetrics mean;
  std::string edits;  // the edit file applied (`glint eval --edits`), empty for the unedited scene
};

struct HtmlReportContent {
  std::string title;
  std::vector<std::pair<std::string, std::string>> facts;  // header lines: label, value
  ViewMetrics mean;
  std::vector<std::pair<std::string, ViewMetrics>> perView;  // view name, its metrics
  std::string evaluationLabel;                               // how `mean` was evaluated
  std::string evaluationEdits;                               // its edit file, empty if unedited
  // The transfer of the 8-bit figures and pictures: "filmic" (Glint's linear datasets) or
  // the display-referred dataset's own ("srgb"), as metrics.json's "display_transfer" says.
  std::string displayTransfer = "filmic";
  std::vector<OtherEvaluation> otherEvaluations;             // more rows of the comparison
  std::vector<ReportView> views;                             // the views shown as images
  std::vector<LineChart> charts;
  std::string chartNote;  // a line under the charts (how to read them)
  std::string configSource;  // the training configuration's file, and its whole text
  std::string configText;
  std::string note;  // a closing line under the page (how it was made)
};

// The whole page. Every text is escaped; NaN metrics show as "-", infinite ones as "inf".
std::string renderHtmlReport(const HtmlReportContent& content);

// "data:image/png;base64,..." of the image tonemapped with tonemapFilmic and quantised to 8 bits.
std::string tonemappedPngDataUri(const Image& linear);
// The same of an image already in display values in [0, 1] (quantised to 8 bits as is).
std::string displayPngDataUri(const Image& shown);

}  // namespace glint
