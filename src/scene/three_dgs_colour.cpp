// 3DGS colour: the display-referred and linear mappings of f_dc, and the export comment.
#include "scene/three_dgs_colour.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/tonemap.h"

namespace glint {

namespace {

constexpr std::string_view kCommentPrefix = "Glint 3DGS export: colour ";
constexpr std::string_view kExposureWord = ", exposure ";

}  // namespace

const char* splatColourName(SplatColour colour) {
  return colour == SplatColour::Display ? "display" : "linear";
}

float encodeSplatColour(float diffuse, const SplatColourEncoding& encoding) {
  if (!std::isfinite(diffuse)) return diffuse;  // kept as is, for the writer to refuse by name
  double shown = encoding.colour == SplatColour::Display ? double(tonemapFilmic(encoding.exposure * diffuse))
                                                         : double(diffuse);
  return float((shown - 0.5) / kShC0);
}

float decodeSplatColour(float fdc, const SplatColourEncoding& encoding) {
  float shown = float(0.5 + kShC0 * double(fdc));
  if (encoding.colour == SplatColour::Linear) return shown;
  return untonemapFilmic(shown) / encoding.exposure;
}

std::string splatColourComment(const SplatColourEncoding& encoding) {
  std::string comment(kCommentPrefix);
  if (encoding.colour == SplatColour::Linear) return comment + "linear (f_dc is the SH DC of the linear diffuse colour)";
  char number[32];
  auto [end, ec] = std::to_chars(number, number + sizeof(number), encoding.exposure);  // shortest exact form
  GLINT_CHECK(ec == std::errc(), "formatting the exposure");
  return comment + "display" + std::string(kExposureWord) + std::string(number, end) +
         " (f_dc is the SH DC of tonemapFilmic(exposure x linear diffuse))";
}

bool isSplatColourComment(const std::string& comment) { return comment.starts_with(kCommentPrefix); }

std::optional<SplatColourEncoding> splatColourFromComments(const std::vector<std::string>& comments,
                                                           const std::string& file) {
  for (const std::string& comment : comments) {
    if (!isSplatColourComment(comment)) continue;
    std::string_view rest = std::string_view(comment).substr(kCommentPrefix.size());
    auto malformed = [&] {
      return Error(file, "unreadable Glint export comment '" + printableText(comment) +
                             "' (expected 'colour linear' or 'colour display, exposure X')");
    };
    SplatColourEncoding encoding;
    if (rest.starts_with("linear")) {
      encoding.colour = SplatColour::Linear;
      return encoding;
    }
    if (!rest.starts_with("display") || !rest.substr(7).starts_with(kExposureWord)) throw malformed();
    std::string_view number = rest.substr(7 + kExposureWord.size());
    auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), encoding.exposure);
    if (ec != std::errc() || !std::isfinite(encoding.exposure) || encoding.exposure <= 0.0f) throw malformed();
    return encoding;
  }
  return std::nullopt;
}

}  // namespace glint
