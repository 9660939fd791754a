// The buffers that `glint render` and `glint eval --save-images` write, and their file
// names, which mirror the dataset's (OUT/depth/depth_0007.exr).
#pragma once

#include <filesystem>
#include <string>

#include "scene/buffers.h"

namespace glint {

constexpr Buffer kRenderedBuffers[] = {Buffer::Render, Buffer::Diffuse, Buffer::Specular, Buffer::Depth,
                                       Buffer::Normal,  Buffer::Roughness, Buffer::F0};

// "test/render/render_0007" -> "OUT/depth/depth_0007.exr" (with format Png: the extension
// bufferStorageFormat gives, so depth stays .exr).
std::filesystem::path renderedBufferPath(const std::filesystem::path& out, const std::string& renderFilePath,
                                         Buffer buffer, ImageFormat format = ImageFormat::Exr);

// "test/render/render_0007" -> "OUT/render_denoised/render_0007.exr": where --denoise puts
// the denoised final image, beside the raw buffers.
std::filesystem::path denoisedRenderPath(const std::filesystem::path& out, const std::string& renderFilePath);

// Writes kRenderedBuffers of one view (each atomically): EXR files of linear values, or 8-bit
// PNG encoded as datasets store them (radiance tonemapped, normals n/2 + 1/2; depth as EXR).
void writeRenderedBuffers(const std::filesystem::path& out, const std::string& renderFilePath,
                          const ViewBuffers& buffers, ImageFormat format = ImageFormat::Exr);

}  // namespace glint
