// File names of rendered buffers, mirroring the dataset layout.
#include "app/rendered_buffers.h"

#include "io/image.h"
#include "scene/buffer_codec.h"
#include "scene/dataset.h"

namespace glint {

std::filesystem::path renderedBufferPath(const std::filesystem::path& out, const std::string& renderFilePath,
                                         Buffer buffer, ImageFormat format) {
  std::filesystem::path relative(bufferFilePath(renderFilePath, buffer));
  return out / relative.parent_path().filename() /
         (relative.filename().string() + imageFormatExtension(bufferStorageFormat(buffer, format)));
}

std::filesystem::path denoisedRenderPath(const std::filesystem::path& out, const std::string& renderFilePath) {
  std::filesystem::path relative(renderFilePath);
  return out / "render_denoised" / (relative.filename().string() + ".exr");
}

void writeRenderedBuffers(const std::filesystem::path& out, const std::string& renderFilePath,
                          const ViewBuffers& buffers, ImageFormat format) {
  for (Buffer b : kRenderedBuffers) {
    ImageFormat stored = bufferStorageFormat(b, format);
    writeImage(renderedBufferPath(out, renderFilePath, b, format), encodeBuffer(buffers[b], b, stored));
  }
}

}  // namespace glint
