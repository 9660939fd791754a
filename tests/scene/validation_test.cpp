// validateDataset accepts a valid dataset and reports each kind of malformed one, naming the
// offending file; Dataset::open / loadView reject the same data where it is theirs to check.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "scene/dataset_summary.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using test::TempFolder;

std::string describe(const std::vector<DatasetProblem>& problems, const fs::path& root) {
  std::string text;
  for (const DatasetProblem& p : problems) text += "  " + formatProblem(p, root) + "\n";
  return text;
}

TEST(Validation, AcceptsAValidDataset) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  std::vector<DatasetProblem> problems = validateDataset(folder.path());
  EXPECT_TRUE(problems.empty()) << describe(problems, folder.path());
}

TEST(Validation, NeverThrowsForAMissingFolder) {
  std::vector<DatasetProblem> problems = validateDataset("/nonexistent/glint/dataset");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].file, "/nonexistent/glint/dataset");
  EXPECT_NE(problems[0].message.find("not found"), std::string::npos);
}

TEST(Validation, CollectsEveryProblemNotJustTheFirst) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  fs::remove(folder / "train/roughness/roughness_0000.exr");
  fs::remove(folder / "train/f0/f0_0001.exr");
  fs::remove(folder / "test/normal/normal_0000.exr");
  std::vector<DatasetProblem> problems = validateDataset(folder.path());
  ASSERT_EQ(problems.size(), 3u) << describe(problems, folder.path());
  // In split and frame order.
  EXPECT_NE(problems[0].file.find("roughness_0000"), std::string::npos);
  EXPECT_NE(problems[1].file.find("f0_0001"), std::string::npos);
  EXPECT_NE(problems[2].file.find("normal_0000"), std::string::npos);
}

// --- Malformed variants -------------------------------------------------------------------

// Which check rejects a variant first: opening, loading the views, or only validation
// (value ranges and the point cloud are validation's business, not the loader's).
enum class RejectedBy { Open, Load, ValidationOnly };

struct Malformed {
  const char* name;
  std::function<void(const fs::path& root)> corrupt;
  const char* file;      // the offending file's name: every reported problem must name it
  const char* fragment;  // part of the expected message
  RejectedBy rejectedBy;
};

void editJson(const fs::path& path, const std::function<void(Json&)>& edit) {
  Json json = Json::parse(readTextFile(path));
  edit(json);
  writeTextAtomically(path, json.dump(2));
}

void editImage(const fs::path& path, const std::function<void(Image&)>& edit) {
  Image image = readImage(path);
  edit(image);
  writeImage(path, image);
}

const Malformed kMalformed[] = {
    // One split alone is a dataset (it renders and evaluates that split); none is not.
    {"MissingBothTransforms",
     [](const fs::path& r) {
       fs::remove(r / "transforms_train.json");
       fs::remove(r / "transforms_test.json");
     },
     "transforms_", "not found", RejectedBy::Open},
    {"JsonSyntaxError",
     [](const fs::path& r) {
       std::string text = readTextFile(r / "transforms_train.json");
       writeTextAtomically(r / "transforms_train.json", text.substr(0, text.rfind('}')));
     },
     "transforms_train.json", "is not valid JSON at byte", RejectedBy::Open},
    {"MissingCameraAngle",
     [](const fs::path& r) { editJson(r / "transforms_train.json", [](Json& j) { j.erase("camera_angle_x"); }); },
     "transforms_train.json", "camera_angle_x is missing", RejectedBy::Open},
    {"CameraAngleOutOfRange",
     [](const fs::path& r) { editJson(r / "transforms_test.json", [](Json& j) { j["camera_angle_x"] = 3.5; }); },
     "transforms_test.json", "must lie in [0.000175, pi)", RejectedBy::Open},
    {"MatrixWithThreeRows",
     [](const fs::path& r) {
       editJson(r / "transforms_train.json", [](Json& j) { j["frames"][1]["transform_matrix"].erase(3); });
     },
     "transforms_train.json", "frame 1: transform_matrix must be 4 rows of 4 numbers", RejectedBy::Open},
    {"NonFiniteMatrixEntry",
     [](const fs::path& r) {
       editJson(r / "transforms_train.json", [](Json& j) { j["frames"][0]["transform_matrix"][0][3] = 1234.5; });
       std::string text = readTextFile(r / "transforms_train.json");
       text.replace(text.find("1234.5"), 6, "NaN");  // what Python's json.dump writes
       writeTextAtomically(r / "transforms_train.json", text);
     },
     "transforms_train.json", "must be finite", RejectedBy::Open},
    {"ScaledMatrix",
     [](const fs::path& r) {
       editJson(r / "transforms_test.json", [](Json& j) {
         Json& m = j["frames"][0]["transform_matrix"];
         for (int row = 0; row < 3; ++row)
           for (int c = 0; c < 3; ++c) m[row][c] = 2.0 * m[row][c].get<double>();
       });
     },
     "transforms_test.json", "frame 0: transform_matrix must be a rigid camera pose", RejectedBy::Open},
    {"MirroredMatrix",
     [](const fs::path& r) {
       editJson(r / "transforms_train.json", [](Json& j) {
         Json& m = j["frames"][1]["transform_matrix"];
         for (int row = 0; row < 3; ++row) m[row][0] = -m[row][0].get<double>();
       });
     },
     "transforms_train.json", "reflection", RejectedBy::Open},
    {"FrameWithoutFilePath",
     [](const fs::path& r) {
       editJson(r / "transforms_train.json", [](Json& j) { j["frames"][0].erase("file_path"); });
     },
     "transforms_train.json", "frame 0: file_path is missing", RejectedBy::Open},
    {"EmptyFramesList",
     [](const fs::path& r) { editJson(r / "transforms_test.json", [](Json& j) { j["frames"] = Json::array(); }); },
     "transforms_test.json", "frames is empty", RejectedBy::Open},
    {"FilePathNotARenderImage",
     [](const fs::path& r) {
       editJson(r / "transforms_test.json", [](Json& j) { j["frames"][0]["file_path"] = "./test/r_0"; });
     },
     "transforms_test.json", "does not name a render image", RejectedBy::Open},
    {"DuplicateFilePath",
     [](const fs::path& r) {
       editJson(r / "transforms_train.json",
                [](Json& j) { j["frames"][1]["file_path"] = j["frames"][0]["file_path"]; });
     },
     "transforms_train.json", "same file_path", RejectedBy::Open},
    {"MissingRoughnessFile", [](const fs::path& r) { fs::remove(r / "train/roughness/roughness_0001.exr"); },
     "roughness_0001", "roughness buffer not found (tried .exr, .tiff and .png)", RejectedBy::Load},
    {"UnsupportedExtension",
     [](const fs::path& r) { fs::rename(r / "train/f0/f0_0001.exr", r / "train/f0/f0_0001.bmp"); }, "f0_0001",
     "tried .exr, .tiff and .png); found f0_0001.bmp", RejectedBy::Load},
    {"WrongImageSize",
     [](const fs::path& r) { writeImage(r / "test/diffuse/diffuse_0000.exr", Image(7, 6, 3, 0.5f)); },
     "diffuse_0000.exr", "image is 7x6 pixels, but the test split's images are 8x6", RejectedBy::Load},
    {"OneChannelNormal",
     [](const fs::path& r) { writeImage(r / "train/normal/normal_0000.exr", Image(8, 6, 1, 1.0f)); },
     "normal_0000.exr", "needs 3 channels, found 1", RejectedBy::Load},
    {"ThreeChannelRoughness",
     [](const fs::path& r) { writeImage(r / "train/roughness/roughness_0000.exr", Image(8, 6, 3, 0.5f)); },
     "roughness_0000.exr", "needs 1 channel, found 3", RejectedBy::Load},
    {"NanInDiffuse",
     [](const fs::path& r) {
       editImage(r / "train/diffuse/diffuse_0001.exr",
                 [](Image& im) { im.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN(); });
     },
     "diffuse_0001.exr", "pixel (3, 2) channel 1 is nan", RejectedBy::Load},
    {"NegativeDepth",
     [](const fs::path& r) { editImage(r / "test/depth/depth_0000.exr", [](Image& im) { im.at(2, 4) = -1.0f; }); },
     "depth_0000.exr", "pixel (2, 4) channel 0 is -1, but depth must not be negative", RejectedBy::Load},
    {"MinusInfinityDepth",
     [](const fs::path& r) {
       editImage(r / "train/depth/depth_0001.exr",
                 [](Image& im) { im.at(5, 1) = -std::numeric_limits<float>::infinity(); });
     },
     "depth_0001.exr", "pixel (5, 1) channel 0 is -inf", RejectedBy::Load},
    {"PngDepth",
     [](const fs::path& r) {
       fs::remove(r / "train/depth/depth_0001.exr");
       writeImage(r / "train/depth/depth_0001.png", Image(8, 6, 1, 0.5f));
     },
     "depth_0001.png", "depth must be stored as float (EXR or TIFF), found PNG", RejectedBy::Load},
    {"TruncatedExr", [](const fs::path& r) { test::truncateToHalf(r / "train/specular/specular_0000.exr"); },
     "specular_0000.exr", "", RejectedBy::Load},
    {"NonUnitNormals",
     [](const fs::path& r) {
       editImage(r / "train/normal/normal_0001.exr", [](Image& im) {
         for (float& v : im.pixels) v *= 0.5f;
       });
     },
     "normal_0001.exr", "not unit length", RejectedBy::ValidationOnly},
    {"RoughnessAboveOne",
     [](const fs::path& r) {
       editImage(r / "test/roughness/roughness_0000.exr", [](Image& im) { im.at(4, 4) = 1.5f; });
     },
     "roughness_0000.exr", "1 of 48 values lie outside [0, 1]; the first is pixel (4, 4) = 1.5", RejectedBy::Load},
    {"F0BelowZero",
     [](const fs::path& r) { editImage(r / "train/f0/f0_0000.exr", [](Image& im) { im.at(1, 1, 2) = -0.2f; }); },
     "f0_0000.exr", "pixel (1, 1) channel 2 = -0.2", RejectedBy::Load},
    {"CorruptPointCloud",
     [](const fs::path& r) { test::writeBytes(r / "point_cloud_dense.ply", "ply\nformat binary_little_endian 1.0\n"); },
     "point_cloud_dense.ply", "", RejectedBy::ValidationOnly},
    {"EmptyPointCloud",
     [](const fs::path& r) {
       test::writeBytes(r / "point_cloud_dense.ply",
                        "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n");
     },
     "point_cloud_dense.ply", "", RejectedBy::ValidationOnly},
};

void PrintTo(const Malformed& variant, std::ostream* out) { *out << variant.name; }

class MalformedDataset : public testing::TestWithParam<Malformed> {};

TEST_P(MalformedDataset, IsRejectedWithAMessageNamingTheFile) {
  const Malformed& variant = GetParam();
  TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  variant.corrupt(folder.path());

  // Validation reports it, and only it: every problem names the offending file.
  std::vector<DatasetProblem> problems = validateDataset(folder.path());
  ASSERT_FALSE(problems.empty());
  bool found = false;
  for (const DatasetProblem& p : problems) {
    std::string text = p.file + ": " + p.message;
    EXPECT_NE(text.find(variant.file), std::string::npos) << text;
    if (text.find(variant.fragment) != std::string::npos) found = true;
  }
  EXPECT_TRUE(found) << "expected \"" << variant.fragment << "\" in:\n" << describe(problems, folder.path());

  // The loader rejects it as early as it should, with the same kind of message.
  auto loadEverything = [&] {
    Dataset dataset = Dataset::open(folder.path());
    if (variant.rejectedBy == RejectedBy::Open) ADD_FAILURE() << "Dataset::open accepted it";
    for (const DatasetSplit* split : {&dataset.train(), &dataset.test()})
      for (size_t v = 0; v < split->views.size(); ++v) dataset.loadView(*split, v);
  };
  if (variant.rejectedBy == RejectedBy::ValidationOnly) {
    EXPECT_NO_THROW(loadEverything());
    return;
  }
  try {
    loadEverything();
    ADD_FAILURE() << "the loader accepted it";
  } catch (const Error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find(variant.file), std::string::npos) << what;
    EXPECT_NE(what.find(variant.fragment), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Variants, MalformedDataset, testing::ValuesIn(kMalformed),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace glint
