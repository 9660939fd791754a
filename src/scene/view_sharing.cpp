// Sharing views over the ranks, and rendered buffers sent to rank 0 as bytes.
#include "scene/view_sharing.h"

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "core/error.h"

namespace glint {

ViewShare::ViewShare(size_t views, bool allowBands)
    : views_(views), banded_(allowBands && cluster::distributed() && views < size_t(cluster::size())) {}

bool ViewShare::mine(size_t v) const { return banded_ || owner(v) == cluster::rank(); }

size_t ViewShare::myCount() const {
  if (banded_) return views_;
  const size_t n = size_t(cluster::size()), r = size_t(cluster::rank());
  return views_ / n + (r < views_ % n ? 1 : 0);
}

cluster::Share ViewShare::myRows(int height) const {
  return banded_ ? cluster::myShare(height) : cluster::Share{0, height};
}

std::string ViewShare::progressLabel(const std::string& label) const {
  if (!cluster::distributed()) return label;
  return label + " (rank 0's " + (banded_ ? "bands" : "share") + " of " + std::to_string(cluster::size()) +
         " ranks)";
}

namespace {

// Each buffer as its width, height and channels (int32) and then its floats, in kAllBuffers
// order. Floats travel as bytes, so the bits arrive unchanged.
std::vector<std::byte> toBytes(const ViewBuffers& buffers) {
  std::vector<std::byte> bytes;
  for (Buffer b : kAllBuffers) {
    const Image& image = buffers[b];
    const int32_t shape[3] = {image.width, image.height, image.channels};
    const size_t at = bytes.size(), floats = image.pixels.size() * sizeof(float);
    bytes.resize(at + sizeof shape + floats);
    std::memcpy(bytes.data() + at, shape, sizeof shape);
    if (floats > 0) std::memcpy(bytes.data() + at + sizeof shape, image.pixels.data(), floats);
  }
  return bytes;
}

ViewBuffers fromBytes(std::span<const std::byte> bytes) {
  ViewBuffers buffers;
  size_t at = 0;
  for (Buffer b : kAllBuffers) {
    int32_t shape[3];
    GLINT_CHECK(at + sizeof shape <= bytes.size(), "view_sharing: truncated buffers");
    std::memcpy(shape, bytes.data() + at, sizeof shape);
    at += sizeof shape;
    Image& image = buffers[b];
    image.width = shape[0];
    image.height = shape[1];
    image.channels = shape[2];
    image.pixels.resize(size_t(shape[0]) * size_t(shape[1]) * size_t(shape[2]));
    const size_t floats = image.pixels.size() * sizeof(float);
    GLINT_CHECK(at + floats <= bytes.size(), "view_sharing: truncated buffers");
    if (floats > 0) std::memcpy(image.pixels.data(), bytes.data() + at, floats);
    at += floats;
  }
  return buffers;
}

}  // namespace

ViewBuffers joinBandsOnRoot(const ViewBuffers& band) {
  if (!cluster::distributed()) return band;
  const std::vector<std::byte> mine = toBytes(band);
  const std::vector<std::vector<std::byte>> all = cluster::gatherToRoot(mine);
  ViewBuffers whole;
  if (!cluster::isRoot()) return whole;
  std::vector<ViewBuffers> bands;
  for (const std::vector<std::byte>& bytes : all) bands.push_back(fromBytes(bytes));
  for (Buffer b : kAllBuffers) {
    Image& image = whole[b];
    // A buffer that a band lacks has no channels (a band of no rows still has them).
    bool complete = true;
    for (const ViewBuffers& part : bands) complete = complete && part[b].channels > 0;
    if (!complete) continue;
    // Bands are whole rows in rank order, so the rows of the image are their concatenation.
    image.width = bands[0][b].width;
    image.channels = bands[0][b].channels;
    for (const ViewBuffers& part : bands) {
      const Image& rows = part[b];
      GLINT_CHECK(rows.width == image.width && rows.channels == image.channels,
                  "joinBandsOnRoot: the bands of a view differ in width or channels");
      image.height += rows.height;
      image.pixels.insert(image.pixels.end(), rows.pixels.begin(), rows.pixels.end());
    }
  }
  return whole;
}

ViewBuffers sendViewToRoot(const ViewBuffers& buffers, int owner) {
  if (!cluster::distributed()) return buffers;
  const bool sending = cluster::rank() == owner && owner != 0;
  const std::vector<std::vector<std::byte>> all = cluster::gatherToRoot(sending ? toBytes(buffers) : std::vector<std::byte>());
  if (!cluster::isRoot()) return ViewBuffers();
  return owner == 0 ? buffers : fromBytes(all[size_t(owner)]);
}

}  // namespace glint
