// The colour of 3DGS files: display and linear encodings invert each other, and the export
// comment is written and read back, with clear errors for a damaged one.
#include "scene/three_dgs_colour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/expect_error.h"
#include "io/tonemap.h"

namespace glint {
namespace {

TEST(ThreeDgsColour, DisplayEncodingIsTheFilmicTonemapOfTheExposedColour) {
  for (float exposure : {1.0f, 0.25f, 3.0f}) {
    SplatColourEncoding encoding{SplatColour::Display, exposure};
    for (float c : {0.0f, 0.001f, 0.05f, 0.3f, 1.0f, 4.0f}) {
      float fdc = encodeSplatColour(c, encoding);
      EXPECT_NEAR(0.5 + kShC0 * fdc, tonemapFilmic(exposure * c), 1e-6) << c;
      EXPECT_NEAR(decodeSplatColour(fdc, encoding), c, 1e-5 + 2e-4 * c) << c << " at exposure " << exposure;
    }
  }
  SplatColourEncoding linear{SplatColour::Linear, 1.0f};
  EXPECT_NEAR(0.5 + kShC0 * encodeSplatColour(2.0f, linear), 2.0, 1e-6);
  EXPECT_NEAR(decodeSplatColour(encodeSplatColour(2.0f, linear), linear), 2.0f, 1e-6);
  // A display colour at or above 1 decodes to the inverse curve's cap, not infinity.
  EXPECT_EQ(decodeSplatColour(float(0.6 / kShC0), SplatColourEncoding{}), kMaxUntonemapped);
  // Non-finite values pass through, for the writer to refuse by name.
  EXPECT_TRUE(std::isinf(encodeSplatColour(std::numeric_limits<float>::infinity(), SplatColourEncoding{})));
}

TEST(ThreeDgsColour, CommentRoundTripsAndDamagedOnesAreRefused) {
  for (SplatColourEncoding encoding : {SplatColourEncoding{SplatColour::Display, 1.0f},
                                       SplatColourEncoding{SplatColour::Display, 0.1f},
                                       SplatColourEncoding{SplatColour::Linear, 1.0f}}) {
    std::string comment = splatColourComment(encoding);
    EXPECT_TRUE(isSplatColourComment(comment)) << comment;
    auto read = splatColourFromComments({"another comment", comment}, "f.ply");
    ASSERT_TRUE(read.has_value()) << comment;
    EXPECT_EQ(read->colour, encoding.colour) << comment;
    EXPECT_EQ(read->exposure, encoding.exposure) << comment;  // shortest exact form: bit for bit
  }
  EXPECT_FALSE(splatColourFromComments({"Glint Gaussian scene: ..."}, "f.ply").has_value());
  for (const char* damaged : {"Glint 3DGS export: colour sepia", "Glint 3DGS export: colour display",
                              "Glint 3DGS export: colour display, exposure -1",
                              "Glint 3DGS export: colour display, exposure nan",
                              "Glint 3DGS export: colour display, exposure x"}) {
    test::expectErrorNaming([&] { splatColourFromComments({damaged}, "damaged.ply"); }, "damaged.ply",
                            {"Glint export comment"});
  }
}

}  // namespace
}  // namespace glint
