// Contact sheet layout and buffer visualisation.
#include "eval/contact_sheet.h"

#include <algorithm>
#include <cmath>

#include "eval/text_overlay.h"
#include "io/tonemap.h"

namespace glint {

namespace {

// A perceptually ordered ramp (dark blue -> teal -> yellow), piecewise linear, so near
// and far read at a glance.
Rgb depthRamp(float t) {
  static const Rgb stops[] = {{0.18f, 0.05f, 0.35f}, {0.15f, 0.35f, 0.6f}, {0.1f, 0.6f, 0.55f},
                              {0.5f, 0.8f, 0.3f},    {0.99f, 0.9f, 0.15f}};
  t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  int i = std::min(3, int(t));
  return lerp(stops[i], stops[i + 1], t - float(i));
}

constexpr int kMargin = 6;
constexpr int kLabelHeight = 22;

}  // namespace

Image visualizeBuffer(const Image& buffer, Buffer kind, float maxDepth) {
  Image out(buffer.width, buffer.height, 3);
  for (int y = 0; y < buffer.height; ++y)
    for (int x = 0; x < buffer.width; ++x) {
      Rgb v = buffer.rgb(x, y);
      Rgb shown;
      switch (kind) {
        case Buffer::Render:
        case Buffer::Diffuse:
        case Buffer::Specular: shown = tonemapFilmic(v); break;
        case Buffer::Depth: shown = hasSurface(v.x) ? depthRamp(v.x / maxDepth) : Rgb(0.0f); break;
        case Buffer::Normal: shown = length(v) > 0 ? v * 0.5f + Rgb(0.5f) : Rgb(0.0f); break;
        case Buffer::Roughness:
        case Buffer::F0: shown = v; break;
      }
      out.setRgb(x, y, min(max(shown, Rgb(0.0f)), Rgb(1.0f)));
    }
  return out;
}

Image makeContactSheet(const Dataset& dataset, const DatasetSplit& split, const std::vector<size_t>& views) {
  // Cells fit the largest of the views (a capture's views may differ in size).
  int w = 0, h = 0;
  for (size_t v : views) w = std::max(w, split.camera(v).width), h = std::max(h, split.camera(v).height);
  // Labels are drawn at scale 2 (7 px font -> 14 px); small images get scale 1.
  const int scale = w >= 96 ? 2 : 1;
  const int columns = kBufferCount;
  const int rowLabelWidth = textWidth("view 0000", scale) + 2 * kMargin;
  Image sheet(rowLabelWidth + columns * (w + kMargin) + kMargin, kLabelHeight + int(views.size()) * (h + kMargin) + kMargin,
              3, 0.12f);
  for (int c = 0; c < columns; ++c) {
    const char* name = bufferName(kAllBuffers[c]);
    int x = rowLabelWidth + c * (w + kMargin) + (w - textWidth(name, scale)) / 2;
    drawText(sheet, x, 5, name, Rgb(0.92f), scale);
  }
  for (size_t r = 0; r < views.size(); ++r) {
    // A capture's view may lack buffers: their cells say so.
    ViewBuffers buffers;
    for (Buffer b : kAllBuffers)
      if (dataset.findBufferFile(split.views[views[r]], b)) buffers[b] = dataset.loadBuffer(split, views[r], b);
    float maxDepth = 0;
    for (float d : buffers[Buffer::Depth].pixels)
      if (hasSurface(d)) maxDepth = std::max(maxDepth, d);
    if (maxDepth <= 0) maxDepth = 1;
    int top = kLabelHeight + int(r) * (h + kMargin);
    char label[32];
    std::snprintf(label, sizeof label, "view %zu", views[r]);
    drawText(sheet, kMargin, top + h / 2 - 4 * scale, label, Rgb(0.92f), scale);
    for (int c = 0; c < columns; ++c) {
      const int left = rowLabelWidth + c * (w + kMargin);
      const Image& buffer = buffers[kAllBuffers[c]];
      if (buffer.empty()) {
        drawText(sheet, left + kMargin, top + h / 2 - 4 * scale, "none", Rgb(0.5f), scale);
        continue;
      }
      Image shown = visualizeBuffer(buffer, kAllBuffers[c], maxDepth);
      for (int y = 0; y < shown.height; ++y)
        for (int x = 0; x < shown.width; ++x) sheet.setRgb(left + x, top + y, shown.rgb(x, y));
    }
  }
  return sheet;
}

}  // namespace glint
