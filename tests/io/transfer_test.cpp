// The transfers of photographs: names, sRGB's known values and break point, and that each
// toDisplay undoes its toLinear (and back) over the whole range a file can store.
#include "io/transfer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "io/tonemap.h"

namespace glint {
namespace {

constexpr Transfer kAll[] = {Transfer::Srgb, Transfer::Filmic, Transfer::Linear};
constexpr float kSrgbBreak = 0.04045f;  // IEC 61966-2-1's break, in display values

TEST(Transfer, NamesRoundTripAndUnknownNamesListTheValidOnes) {
  EXPECT_STREQ(transferName(Transfer::Srgb), "srgb");
  EXPECT_STREQ(transferName(Transfer::Filmic), "filmic");
  EXPECT_STREQ(transferName(Transfer::Linear), "linear");
  for (Transfer t : kAll) EXPECT_EQ(parseTransfer(transferName(t)), t);
  for (const char* bad : {"gamma", "sRGB", "", "srgb "}) {
    try {
      parseTransfer(bad);
      ADD_FAILURE() << "no error for '" << bad << "'";
    } catch (const Error& e) {
      std::string message = e.what();
      EXPECT_NE(message.find("'" + std::string(bad) + "'"), std::string::npos) << message;
      for (const char* valid : {"srgb", "filmic", "linear"})
        EXPECT_NE(message.find(valid), std::string::npos) << message;
    }
  }
}

TEST(Transfer, SrgbKnownValues) {
  // Reference values from the standard's formulas evaluated in double.
  EXPECT_EQ(toLinear(Transfer::Srgb, 0.0f), 0.0f);
  EXPECT_EQ(toLinear(Transfer::Srgb, 1.0f), 1.0f);
  EXPECT_EQ(toDisplay(Transfer::Srgb, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(toDisplay(Transfer::Srgb, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(toLinear(Transfer::Srgb, 0.5f), 0.21404114f);
  EXPECT_FLOAT_EQ(toLinear(Transfer::Srgb, 128.0f / 255.0f), 0.21586050f);
  EXPECT_FLOAT_EQ(toLinear(Transfer::Srgb, 0.02f), 0.02f / 12.92f);  // the linear segment
  EXPECT_FLOAT_EQ(toDisplay(Transfer::Srgb, 0.18f), 0.46135613f);    // middle grey
  EXPECT_FLOAT_EQ(toDisplay(Transfer::Srgb, 0.5f), 0.73535698f);
}

// The standard's rounded constants leave the two segments 2.3e-9 apart at the break (in
// linear values); nothing larger may appear there, in either direction.
TEST(Transfer, SrgbIsContinuousAtTheBreak) {
  float below = std::nextafter(kSrgbBreak, 0.0f), above = std::nextafter(kSrgbBreak, 1.0f);
  float atBreak = toLinear(Transfer::Srgb, kSrgbBreak);
  EXPECT_FLOAT_EQ(atBreak, kSrgbBreak / 12.92f);
  EXPECT_LT(toLinear(Transfer::Srgb, below), atBreak);
  EXPECT_GT(toLinear(Transfer::Srgb, above), atBreak);
  EXPECT_LT(toLinear(Transfer::Srgb, above) - atBreak, 3e-9f);
  // The slopes of the two segments differ by under 2% there (1/12.92 against 0.0787).
  float step = 1e-4f;
  float slopeBelow = (atBreak - toLinear(Transfer::Srgb, kSrgbBreak - step)) / step;
  float slopeAbove = (toLinear(Transfer::Srgb, kSrgbBreak + step) - atBreak) / step;
  EXPECT_NEAR(slopeAbove / slopeBelow, 1.0f, 0.02f);
  // And the inverse, around the break's image.
  float linearAbove = std::nextafter(atBreak, 1.0f);
  EXPECT_FLOAT_EQ(toDisplay(Transfer::Srgb, atBreak), kSrgbBreak);
  EXPECT_LT(std::abs(toDisplay(Transfer::Srgb, linearAbove) - kSrgbBreak), 4e-8f);
}

TEST(Transfer, SrgbIsMonotonic) {
  float previousLinear = toLinear(Transfer::Srgb, 0.0f), previousDisplay = toDisplay(Transfer::Srgb, 0.0f);
  for (int i = 1; i <= 100000; ++i) {
    float v = float(i) / 100000.0f;
    float linear = toLinear(Transfer::Srgb, v), display = toDisplay(Transfer::Srgb, v);
    ASSERT_GT(linear, previousLinear) << v;
    ASSERT_GT(display, previousDisplay) << v;
    previousLinear = linear, previousDisplay = display;
  }
}

// Every 16-bit code (so every 8-bit one), a dense grid over [0, 1], and values beyond it:
// display -> linear -> display returns the value to within a few float steps.
TEST(Transfer, SrgbDisplayRoundTrip) {
  auto expectRoundTrip = [](float v) {
    float back = toDisplay(Transfer::Srgb, toLinear(Transfer::Srgb, v));
    ASSERT_NEAR(back, v, 4.0f * std::numeric_limits<float>::epsilon() * std::max(std::abs(v), 1e-30f)) << v;
  };
  for (int code = 0; code <= 65535; ++code) expectRoundTrip(float(code) / 65535.0f);
  for (int i = 0; i <= 1000000; ++i) expectRoundTrip(float(i) / 1000000.0f);
  for (float v : {-0.5f, -1e-3f, 1.5f, 4.0f, kSrgbBreak, std::nextafter(kSrgbBreak, 1.0f)}) expectRoundTrip(v);
}

// Linear -> display -> linear, on a log grid from 1e-6 to 16 and around the break's image.
TEST(Transfer, SrgbLinearRoundTrip) {
  for (int i = 0; i <= 100000; ++i) {
    float l = 1e-6f * std::pow(16e6f, float(i) / 100000.0f);
    float back = toLinear(Transfer::Srgb, toDisplay(Transfer::Srgb, l));
    ASSERT_NEAR(back, l, 8.0f * std::numeric_limits<float>::epsilon() * l) << l;
  }
  float atBreak = toLinear(Transfer::Srgb, kSrgbBreak);
  for (float l = atBreak * 0.999f; l < atBreak * 1.001f; l = std::nextafter(l, 1.0f)) {
    float back = toLinear(Transfer::Srgb, toDisplay(Transfer::Srgb, l));
    ASSERT_NEAR(back, l, 8.0f * std::numeric_limits<float>::epsilon() * l) << l;
  }
  // The linear segment continues below zero, so negatives (noise) come back too.
  EXPECT_FLOAT_EQ(toLinear(Transfer::Srgb, toDisplay(Transfer::Srgb, -0.01f)), -0.01f);
}

TEST(Transfer, FilmicIsTheTonemapAndRoundTrips) {
  for (float x : {0.0f, 0.01f, 0.5f, 1.0f, 7.0f, 60.0f}) {
    EXPECT_EQ(toDisplay(Transfer::Filmic, x), tonemapFilmic(x));
    // The inverse's published constants are rounded to 4 digits: 1e-4 relative.
    EXPECT_NEAR(toLinear(Transfer::Filmic, toDisplay(Transfer::Filmic, x)), x, 1e-4f * std::max(1.0f, x)) << x;
  }
  // Back from display values the rounded constants leave up to about 1.2e-5, a three
  // hundredth of an 8-bit step: every code below white decodes and re-encodes to itself.
  for (int code = 0; code < 255; ++code) {
    float y = float(code) / 255.0f;
    EXPECT_EQ(toLinear(Transfer::Filmic, y), untonemapFilmic(y));
    float back = toDisplay(Transfer::Filmic, toLinear(Transfer::Filmic, y));
    EXPECT_NEAR(back, y, 2e-5f) << code;
    EXPECT_EQ(std::lround(back * 255.0f), code);
  }
  EXPECT_EQ(toLinear(Transfer::Filmic, 1.0f), kMaxUntonemapped);  // white saturates
}

TEST(Transfer, LinearIsTheIdentity) {
  for (float v : {-2.0f, 0.0f, 0.25f, 1.0f, 1e6f}) {
    EXPECT_EQ(toLinear(Transfer::Linear, v), v);
    EXPECT_EQ(toDisplay(Transfer::Linear, v), v);
  }
}

// Images take a table look-up for values that are 8- or 16-bit codes; it must give exactly
// what the per-value function gives, for codes and for any other value.
TEST(Transfer, ImagesGiveExactlyThePerValueResult) {
  std::vector<float> values;
  for (int k = 0; k <= 65535; ++k) values.push_back(float(k) / 65535.0f);
  for (int c = 0; c <= 255; ++c) values.push_back(float(c) / 255.0f);
  for (float v : {-0.25f, -0.0f, 0.3f, 0.5f + 1e-7f, std::nextafter(1.0f, 2.0f), 1.5f, 300.0f}) values.push_back(v);
  Image image(int(values.size()), 1, 1);
  image.pixels = values;
  for (Transfer t : kAll) {
    Image linear = toLinear(t, image);
    for (size_t i = 0; i < values.size(); ++i)
      ASSERT_EQ(linear.pixels[i], toLinear(t, values[i])) << transferName(t) << " at " << values[i];
  }
  Image notANumber(1, 1, 1, std::numeric_limits<float>::quiet_NaN());
  EXPECT_TRUE(std::isnan(toLinear(Transfer::Srgb, notANumber).pixels[0]));
}

TEST(Transfer, ImagesChangeTheirColourChannelsOnly) {
  Image rgba(2, 1, 4);
  rgba.pixels = {0.5f, 0.25f, 0.9f, 0.5f, 0.0f, 0.75f, 0.1f, 0.3f};  // below 1: filmic white saturates
  for (Transfer t : kAll) {
    Image linear = toLinear(t, rgba);
    for (int x = 0; x < 2; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(linear.at(x, 0, c), toLinear(t, rgba.at(x, 0, c))) << transferName(t);
      EXPECT_EQ(linear.at(x, 0, 3), rgba.at(x, 0, 3)) << "alpha is coverage, not colour";
    }
    Image back = toDisplay(t, linear);
    for (size_t i = 0; i < rgba.pixels.size(); ++i) EXPECT_NEAR(back.pixels[i], rgba.pixels[i], 2e-5f) << i;
  }
  Image grey(3, 1, 1);
  grey.pixels = {0.0f, 0.5f, 1.0f};
  Image linear = toLinear(Transfer::Srgb, grey);
  ASSERT_EQ(linear.channels, 1);
  EXPECT_FLOAT_EQ(linear.pixels[1], 0.21404114f);
  EXPECT_EQ(toLinear(Transfer::Srgb, Image()).pixels.size(), 0u);
}

}  // namespace
}  // namespace glint
