// The sRGB, filmic and linear transfers, per value and over an image's colour channels.
#include "io/transfer.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/tonemap.h"

namespace glint {

namespace {

constexpr Transfer kAllTransfers[] = {Transfer::Srgb, Transfer::Filmic, Transfer::Linear};

// IEC 61966-2-1: display V <= 0.04045 is linear, L = V / 12.92; above, L = ((V + 0.055) /
// 1.055)^2.4. The standard's encoder switches at L = 0.0031308, a rounding of the decoder's
// break mapped through the linear segment; here the encoder switches at the exact image
// of the float break instead, so that each value goes back through the branch it came
// from and the pair is inverse everywhere. The standard's rounded constants leave a jump
// of 2.3e-9 in L at the break, about 10 float steps there and far below a 16-bit code.
constexpr float kSrgbDisplayBreak = 0.04045f;
constexpr double kSrgbSlope = 12.92;
constexpr float kSrgbLinearBreak = float(double(kSrgbDisplayBreak) / kSrgbSlope);
constexpr double kSrgbOffset = 0.055;
constexpr double kSrgbGamma = 2.4;

// Evaluated in double and rounded once, so the round trip loses at most a few float steps.
float srgbToLinear(float v) {
  if (v <= kSrgbDisplayBreak) return float(double(v) / kSrgbSlope);
  return float(std::pow((double(v) + kSrgbOffset) / (1.0 + kSrgbOffset), kSrgbGamma));
}

float srgbToDisplay(float l) {
  if (l <= kSrgbLinearBreak) return float(double(l) * kSrgbSlope);
  return float((1.0 + kSrgbOffset) * std::pow(double(l), 1.0 / kSrgbGamma) - kSrgbOffset);
}

// toLinear of every 16-bit code k / 65535, for images read from 8- and 16-bit files: their
// values are all of that form, since c / 255 = 257 c / 65535 and a float division rounds the
// same quotient to the same float. A 12-megapixel photograph then costs 36 million look-ups
// instead of as many calls of pow; any other value is computed as toLinear(float) does.
class CodeTable {
 public:
  static constexpr int kMaxCode = 65535;

  explicit CodeTable(Transfer transfer) : transfer_(transfer), linear_(kMaxCode + 1) {
    for (int k = 0; k <= kMaxCode; ++k) linear_[size_t(k)] = glint::toLinear(transfer, float(k) / float(kMaxCode));
  }

  float toLinear(float display) const {
    if (display >= 0.0f && display <= 1.0f) {
      int k = int(display * float(kMaxCode) + 0.5f);  // the nearest code; display is in [0, 1]
      if (float(k) / float(kMaxCode) == display) return linear_[size_t(k)];
    }
    return glint::toLinear(transfer_, display);
  }

 private:
  Transfer transfer_;
  std::vector<float> linear_;
};

// The table of a curved transfer (Linear needs none), built on first use: 256 KB each.
const CodeTable& codeTable(Transfer transfer) {
  GLINT_CHECK(transfer != Transfer::Linear, "the linear transfer has no code table");
  static const CodeTable srgb(Transfer::Srgb), filmic(Transfer::Filmic);
  return transfer == Transfer::Srgb ? srgb : filmic;
}

// Applies f to the colour channels of every pixel: the first three, or the only one.
template <typename F>
Image mapColourChannels(Image image, F f) {
  if (image.channels <= 0) return image;  // nothing to map (and no stride to step by)
  int colourChannels = std::min(image.channels, 3);
  for (size_t p = 0; p < image.pixels.size(); p += size_t(image.channels)) {
    for (int c = 0; c < colourChannels; ++c) image.pixels[p + size_t(c)] = f(image.pixels[p + size_t(c)]);
  }
  return image;
}

}  // namespace

const char* transferName(Transfer transfer) {
  switch (transfer) {
    case Transfer::Srgb: return "srgb";
    case Transfer::Filmic: return "filmic";
    case Transfer::Linear: return "linear";
  }
  return "unknown";
}

Transfer parseTransfer(const std::string& name) {
  for (Transfer t : kAllTransfers)
    if (name == transferName(t)) return t;
  throw Error("unknown transfer '" + printableText(name) + "' (expected srgb, filmic or linear)");
}

float toLinear(Transfer transfer, float display) {
  switch (transfer) {
    case Transfer::Srgb: return srgbToLinear(display);
    case Transfer::Filmic: return untonemapFilmic(display);
    case Transfer::Linear: return display;
  }
  return display;
}

float toDisplay(Transfer transfer, float linear) {
  switch (transfer) {
    case Transfer::Srgb: return srgbToDisplay(linear);
    case Transfer::Filmic: return tonemapFilmic(linear);
    case Transfer::Linear: return linear;
  }
  return linear;
}

Image toLinear(Transfer transfer, Image image) {
  if (transfer == Transfer::Linear) return image;
  const CodeTable& table = codeTable(transfer);
  return mapColourChannels(std::move(image), [&table](float v) { return table.toLinear(v); });
}

Image toDisplay(Transfer transfer, Image image) {
  if (transfer == Transfer::Linear) return image;
  return mapColourChannels(std::move(image), [transfer](float v) { return toDisplay(transfer, v); });
}

}  // namespace glint
