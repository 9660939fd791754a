// `glint report` end to end on a tiny run (synth, train, eval --save-images, report): the
// page holds the run's metrics, views and curves; missing or corrupt inputs are named.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::readBytes;
using test::runGlint;

int countOf(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class ReportCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("glint_report_cli_test_" + std::to_string(getpid())));
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    Outcome synth =
        runGlint("synth builtin:spheres -o " + path("D") + " --train 6 --test 2 --res 32x24 --spp 4");
    ASSERT_EQ(synth.status, 0) << synth.output;
    Outcome train = runGlint("train " + path("D") + " -o " + path("R") +
                             " --iters 40 --batch-rays 256 --eval-every 20 --eval-views 2 --threads 2 --seed 1");
    ASSERT_EQ(train.status, 0) << train.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }
  static std::string path(const std::string& name) { return (*root_ / name).string(); }
  static fs::path* root_;
};

fs::path* ReportCliTest::root_ = nullptr;

TEST_F(ReportCliTest, WritesTheRunsPageAndNamesMissingInputs) {
  // Before eval: the metrics are missing, and the message says what makes them.
  Outcome early = runGlint("report " + path("R"));
  EXPECT_NE(early.status, 0);
  EXPECT_NE(early.output.find("eval/metrics.json: not found; run `glint eval " + path("R") + " --save-images` first"),
            std::string::npos)
      << early.output;
  EXPECT_FALSE(fs::exists(path("R") + "/report.html"));

  // Eval without images: the first missing image is named.
  ASSERT_EQ(runGlint("eval " + path("R") + " --spp 2").status, 0);
  Outcome noImages = runGlint("report " + path("R"));
  EXPECT_NE(noImages.status, 0);
  EXPECT_NE(noImages.output.find("eval/test/diffuse/diffuse_0000.exr: not found"), std::string::npos)
      << noImages.output;
  EXPECT_NE(noImages.output.find("--save-images"), std::string::npos) << noImages.output;

  Outcome eval = runGlint("eval " + path("R") + " --spp 2 --save-images");
  ASSERT_EQ(eval.status, 0) << eval.output;
  Outcome report = runGlint("report " + path("R"));
  ASSERT_EQ(report.status, 0) << report.output;
  EXPECT_NE(report.output.find("report.html"), std::string::npos) << report.output;
  std::string html = readBytes(path("R") + "/report.html");
  ASSERT_FALSE(html.empty());

  // The page shows the metrics of metrics.json, both views and the training curves.
  nlohmann::json metrics = nlohmann::json::parse(readBytes(path("R") + "/eval/metrics.json"));
  for (const char* pass : {"diffuse", "specular", "final"}) {
    char expected[64];
    std::snprintf(expected, sizeof expected, "<td>%.2f</td>", metrics["mean"][pass]["psnr_tonemapped"].get<double>());
    EXPECT_NE(html.find(std::string("<tr><td>") + pass + "</td>"), std::string::npos) << pass;
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  }
  EXPECT_EQ(countOf(html, "<section class=\"view\">"), 2);
  EXPECT_EQ(countOf(html, "<td>test/render/render_000"), 2);
  // Per view: ground truth, ours and error map of three passes; ground truth and ours of
  // the normal, depth, roughness and F0 buffers.
  EXPECT_EQ(countOf(html, "src=\"data:image/png;base64,"), 2 * (3 * 3 + 4 * 2));
  EXPECT_NE(html.find("<h2>Training configuration</h2>"), std::string::npos);
  EXPECT_NE(html.find("&quot;render_bounces&quot;: 4"), std::string::npos);  // the whole config, defaults too
  EXPECT_EQ(html.find("Edit consistency"), std::string::npos);
  EXPECT_EQ(countOf(html, "<svg "), 4);  // loss, L1 terms, Gaussians, test PSNR
  EXPECT_NE(html.find("<dd>40 of 40"), std::string::npos);  // steps from the log and config
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);

  // -o writes elsewhere (with --views), and does not overwrite a file there without --force.
  Outcome some = runGlint("report " + path("R") + " --views 1 -o " + path("page.html"));
  ASSERT_EQ(some.status, 0) << some.output;
  EXPECT_EQ(countOf(readBytes(path("page.html")), "<section class=\"view\">"), 1);
  Outcome again = runGlint("report " + path("R") + " -o " + path("page.html"));
  EXPECT_NE(again.status, 0);
  EXPECT_NE(again.output.find("page.html: exists; pass --force"), std::string::npos) << again.output;
  EXPECT_EQ(runGlint("report " + path("R") + " -o " + path("page.html") + " --force").status, 0);
  EXPECT_EQ(countOf(readBytes(path("page.html")), "<section class=\"view\">"), 2);
  // The run's own page is rewritten without --force.
  EXPECT_EQ(runGlint("report " + path("R")).status, 0);
  EXPECT_EQ(html.find("All evaluations of this run"), std::string::npos);  // only one so far

  // Other metrics files of the run become rows of a comparison table, with their settings;
  // a JSON file that is not one is left out with a note naming it.
  Outcome second =
      runGlint("eval " + path("R") + " --spp 3 --bounces 1 --denoise specular -o " + path("R") + "/eval/second.json");
  ASSERT_EQ(second.status, 0) << second.output;
  std::ofstream(path("R") + "/eval/notes.json") << "{\"mine\": 1}";
  nlohmann::json trainSplit = nlohmann::json::parse(readBytes(path("R") + "/eval/second.json"));
  trainSplit["split"] = "train";
  std::ofstream(path("R") + "/eval/train_split.json") << trainSplit.dump();
  Outcome compared = runGlint("report " + path("R"));
  ASSERT_EQ(compared.status, 0) << compared.output;
  EXPECT_NE(compared.output.find("notes.json: key \"mean\" is missing"), std::string::npos) << compared.output;
  EXPECT_NE(compared.output.find("train_split.json: evaluated the train split, not test"), std::string::npos)
      << compared.output;
  html = readBytes(path("R") + "/report.html");
  EXPECT_NE(html.find("All evaluations of this run"), std::string::npos);
  EXPECT_NE(html.find("<td>metrics.json: 2 spp, 4 bounces (this page)</td>"), std::string::npos);  // render_bounces
  EXPECT_NE(html.find("<td>second.json: 3 spp, 1 bounces, denoised specular</td>"), std::string::npos);
  nlohmann::json secondMetrics = nlohmann::json::parse(readBytes(path("R") + "/eval/second.json"));
  EXPECT_EQ(secondMetrics["bounces"], 1);
  char finalCell[64];
  std::snprintf(finalCell, sizeof finalCell, "<td>%.2f</td>",
                secondMetrics["mean"]["final"]["psnr_tonemapped"].get<double>());
  EXPECT_NE(html.find(finalCell), std::string::npos) << finalCell;
  EXPECT_EQ(html.find("notes.json"), std::string::npos);
  EXPECT_EQ(html.find("train_split.json"), std::string::npos);

  // An evaluation with --edits gets a row of the edit-consistency table, with its drop.
  std::ofstream(path("edits.json"))
      << R"({"glint_edits": 1, "selections": {"all": "everything"},
            "operations": [{"op": "roughness", "selection": "all", "set": 0.9}]})";
  Outcome edited = runGlint("eval " + path("R") + " --spp 2 --edits " + path("edits.json") + " -o " + path("R") +
                            "/eval/edited.json");
  ASSERT_EQ(edited.status, 0) << edited.output;
  ASSERT_EQ(runGlint("report " + path("R")).status, 0);
  html = readBytes(path("R") + "/report.html");
  size_t table = html.find("<h2>Edit consistency</h2>");
  ASSERT_NE(table, std::string::npos);
  nlohmann::json editedMetrics = nlohmann::json::parse(readBytes(path("R") + "/eval/edited.json"));
  char drop[64];
  std::snprintf(drop, sizeof drop, "<td>%.2f dB</td></tr>",
                metrics["mean"]["final"]["psnr_tonemapped"].get<double>() -
                    editedMetrics["mean"]["final"]["psnr_tonemapped"].get<double>());
  size_t row = html.find("<tr><td>" + path("edits.json") + "</td>", table);
  ASSERT_NE(row, std::string::npos);
  std::string cells = html.substr(row, html.find("</tr>", row) + 5 - row);
  EXPECT_TRUE(cells.ends_with(drop)) << cells << " does not end with the final pass's drop " << drop;
}

TEST_F(ReportCliTest, CorruptInputsAreNamed) {
  fs::copy(path("R"), path("C"), fs::copy_options::recursive);
  ASSERT_EQ(runGlint("eval " + path("C") + " --spp 1 --save-images").status, 0);
  ASSERT_EQ(runGlint("report " + path("C")).status, 0);

  std::string log = readBytes(path("C") + "/log.csv");
  std::ofstream(path("C") + "/log.csv", std::ios::app) << "41,oops\n";
  Outcome badLog = runGlint("report " + path("C"));
  EXPECT_NE(badLog.status, 0);
  EXPECT_NE(badLog.output.find("log.csv: line 42: 2 fields"), std::string::npos) << badLog.output;
  std::ofstream(path("C") + "/log.csv", std::ios::trunc) << log;

  std::string metrics = readBytes(path("C") + "/eval/metrics.json");
  std::ofstream(path("C") + "/eval/metrics.json", std::ios::trunc) << metrics.substr(0, metrics.size() / 2);
  Outcome truncated = runGlint("report " + path("C"));
  EXPECT_NE(truncated.status, 0);
  EXPECT_NE(truncated.output.find("metrics.json: is not valid JSON"), std::string::npos) << truncated.output;
  nlohmann::json j = nlohmann::json::parse(metrics);
  j["per_view"][1]["final"].erase("psnr");
  std::ofstream(path("C") + "/eval/metrics.json", std::ios::trunc) << j.dump();
  Outcome missingKey = runGlint("report " + path("C"));
  EXPECT_NE(missingKey.status, 0);
  EXPECT_NE(missingKey.output.find("per_view[1].final.psnr"), std::string::npos) << missingKey.output;

  fs::remove(path("C") + "/config.json");
  Outcome noConfig = runGlint("report " + path("C"));
  EXPECT_NE(noConfig.status, 0);
  EXPECT_NE(noConfig.output.find("config.json: not found; it is written by `glint train"), std::string::npos)
      << noConfig.output;
  Outcome notARun = runGlint("report " + path("nothing"));
  EXPECT_NE(notARun.status, 0);
  EXPECT_NE(notARun.output.find("nothing: is not a training run folder"), std::string::npos) << notARun.output;
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// An evaluation against another dataset than the run's (an edited scene's ground truth) is
// reported against that dataset's images, which metrics.json names; when it has gone,
// the message says so and --dataset points elsewhere.
TEST_F(ReportCliTest, ShowsTheDatasetTheMetricsWereEvaluatedOn) {
  const std::string run = path("R_other");
  fs::copy(path("R"), run, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::remove_all(run + "/eval");
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D_other") + " --train 6 --test 2 --res 32x24 --spp 2");
  ASSERT_EQ(synth.status, 0) << synth.output;
  // From another working folder, with a relative path: metrics.json records where it is.
  const fs::path here = fs::current_path();
  fs::current_path(*root_);
  Outcome eval = runGlint("eval " + run + " --dataset D_other --spp 2 --save-images");
  fs::current_path(here);
  ASSERT_EQ(eval.status, 0) << eval.output;
  nlohmann::json metrics = nlohmann::json::parse(readBytes(run + "/eval/metrics.json"));
  EXPECT_EQ(fs::path(metrics["dataset"].get<std::string>()), fs::path(path("D_other")));

  Outcome report = runGlint("report " + run);
  ASSERT_EQ(report.status, 0) << report.output;
  std::string html = readBytes(run + "/report.html");
  // Named relative to the run (the page names no one's home folder).
  EXPECT_NE(html.find("<dd>../D_other (test split"), std::string::npos);
  EXPECT_EQ(html.find("../D (test split"), std::string::npos);
  const size_t absolute = html.find(root_->string());
  EXPECT_EQ(absolute, std::string::npos)
      << "an absolute path in the report: " << html.substr(absolute == std::string::npos ? 0 : absolute - 80, 200);

  fs::rename(path("D_other"), path("D_moved"));
  Outcome gone = runGlint("report " + run);
  EXPECT_NE(gone.status, 0);
  EXPECT_NE(gone.output.find("metrics.json: evaluated the dataset " + path("D_other") +
                             ", which is not found; pass --dataset"),
            std::string::npos)
      << gone.output;
  Outcome pointed = runGlint("report " + run + " --dataset " + path("D_moved"));
  ASSERT_EQ(pointed.status, 0) << pointed.output;
  EXPECT_NE(readBytes(run + "/report.html").find("<dd>../D_moved (test split"), std::string::npos);
}

}  // namespace
}  // namespace glint
