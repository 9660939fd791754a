// OpenEXR reading (half or float; RGB or one channel) and writing (float32) through OpenEXR 3.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/image_codecs.h"

namespace glint::detail {

namespace {

// Which of the file's channels become the image's channels, or an Error naming the layout.
std::vector<std::string> chooseExrChannels(const std::string& path, const Imf::ChannelList& channels) {
  std::vector<std::string> names;
  for (auto it = channels.begin(); it != channels.end(); ++it) names.push_back(it.name());
  for (const std::string& name : names) {
    const Imf::Channel& channel = channels[name];
    if (channel.xSampling != 1 || channel.ySampling != 1) {
      throw Error(path, "EXR channel '" + printableText(name) + "' is subsampled, which is not supported");
    }
  }
  // Colour images: R, G, B; alpha and any other channels (e.g. Z stored alongside) are ignored.
  if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B")) return {"R", "G", "B"};
  // Scalar images (depth, roughness, ...): the single channel, whatever its name.
  if (names.size() == 1) return names;
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + printableText(name);
  throw Error(path, "unsupported EXR channels {" + list + "} (expected R, G, B [, A] or a single channel)");
}

}  // namespace

Image readExr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    std::vector<std::string> names = chooseExrChannels(path, header.channels());
    Imath::Box2i window = header.dataWindow();
    long width = long(window.max.x) - window.min.x + 1;
    long height = long(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0) throw Error(path, "EXR data window is empty");
    checkImageSize(path, size_t(width), size_t(height), names.size(), 2);  // half: the smallest sample

    Image image(int(width), int(height), int(names.size()));
    // OpenEXR addresses the buffer with absolute pixel coordinates, so shift the base by
    // the data window's origin; it converts half (or uint) to float while reading.
    Imf::FrameBuffer frame;
    size_t xStride = sizeof(float) * names.size();
    size_t yStride = xStride * size_t(width);
    for (size_t c = 0; c < names.size(); ++c) {
      frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window, xStride, yStride));
    }
    file.setFrameBuffer(frame);
    // Pixels are decoded here, not in the constructor: truncation surfaces now.
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path, "cannot read EXR: " + printableText(e.what(), std::string::npos));  // may quote the file
  }
}

void writeExr(const std::string& filePath, const std::string& displayPath, const Image& image) {
  static const char* const kRgbNames[] = {"R", "G", "B"};
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless, and what most tools write
    for (int c = 0; c < image.channels; ++c) {
      header.channels().insert(image.channels == 1 ? "Y" : kRgbNames[c], Imf::Channel(Imf::FLOAT));
    }
    Imf::FrameBuffer frame;
    size_t xStride = sizeof(float) * image.channels;
    size_t yStride = xStride * image.width;
    // OpenEXR's API takes a mutable pointer but only reads from it when writing.
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.pixels.data()));
    for (int c = 0; c < image.channels; ++c) {
      frame.insert(image.channels == 1 ? "Y" : kRgbNames[c],
                   Imf::Slice(Imf::FLOAT, base + sizeof(float) * c, xStride, yStride));
    }
    // Write through our own stream: OutputFile writes its offset table in its destructor,
    // which swallows errors, so a full disk only shows in the stream's state afterwards.
    std::ofstream stream(filePath, std::ios::binary);
    if (!stream) throw Error(displayPath, "cannot open for writing");
    {
      Imf::StdOFStream exrStream(stream, filePath.c_str());
      Imf::OutputFile file(exrStream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }
    stream.close();
    if (!stream) throw Error(displayPath, "write failed (disk full?)");
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(displayPath, std::string("cannot write EXR: ") + e.what());
  }
}

}  // namespace glint::detail
