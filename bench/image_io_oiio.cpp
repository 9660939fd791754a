// OpenImageIO's readers and resize, called as image_io_bench compares them with Glint's.
#include "image_io_oiio.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace glint {

namespace {

// OpenImageIO's thread attributes as the library starts, read before the first change.
struct ThreadDefaults {
  int threads = 0;
  int exrThreads = 0;
};

const ThreadDefaults& threadDefaults() {
  static const ThreadDefaults defaults = [] {
    ThreadDefaults d;
    OIIO::getattribute("threads", d.threads);
    OIIO::getattribute("exr_threads", d.exrThreads);
    return d;
  }();
  return defaults;
}

}  // namespace

std::string oiioDescription() {
  std::string libraries;
  OIIO::getattribute("library_list", libraries);
  return "OpenImageIO " OIIO_VERSION_STRING " (" + libraries + ")";
}

void useOiioSingleThread() {
  threadDefaults();
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", -1);  // -1: OpenEXR decodes in the calling thread
}

void useOiioDefaultThreads() {
  OIIO::attribute("threads", threadDefaults().threads);
  OIIO::attribute("exr_threads", threadDefaults().exrThreads);
}

Image readWithOiio(const std::filesystem::path& path, int channels) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path.string(), &config);
  if (!input) throw std::runtime_error(path.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.nchannels < channels) {
    throw std::runtime_error(path.string() + ": " + std::to_string(spec.nchannels) + " channels, expected " +
                             std::to_string(channels));
  }
  Image image(spec.width, spec.height, channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw std::runtime_error(path.string() + ": " + input->geterror());
  }
  return image;
}

Image downscaleWithOiio(const Image& image, int n) {
  Image small(image.width / n, image.height / n, image.channels);
  // Both buffers wrap the Images' own memory; the source is only read.
  OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT),
                        const_cast<float*>(image.pixels.data()));
  OIIO::ImageBuf destination(OIIO::ImageSpec(small.width, small.height, small.channels, OIIO::TypeDesc::FLOAT),
                             small.pixels.data());
  if (!OIIO::ImageBufAlgo::resize(destination, source, "box", 1.0f)) {
    throw std::runtime_error("OpenImageIO resize: " + destination.geterror());
  }
  return small;
}

}  // namespace glint
