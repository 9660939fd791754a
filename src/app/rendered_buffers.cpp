// File names of rendered buffers, mirroring the dataset layout.
#include "app/rendered_buffers.h"

#include "io/image.h"
#include "scene/dataset.h"

namespace glint {

std::filesystem::path renderedBufferPath(const std::filesystem::path& out, const std::string& renderFilePath,
                                         Buffer buffer) {
  std::filesystem::path relative(bufferFilePath(renderFilePath, buffer));
  return out / relative.parent_path().filename() / (relative.filename().string() + ".exr");
}

std::filesystem::path denoisedRenderPath(const std::filesystem::path& out, const std::string& renderFilePath) {
  std::filesystem::path relative(renderFilePath);
  return out / "render_denoised" / (relative.filename().string() + ".exr");
}

void writeRenderedBuffers(const std::filesystem::path& out, const std::string& renderFilePath,
                          const ViewBuffers& buffers) {
  for (Buffer b : kRenderedBuffers) writeImage(renderedBufferPath(out, renderFilePath, b), buffers[b]);
}

}  // namespace glint
