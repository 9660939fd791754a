// Names, channel counts and allocation of the seven per-view buffers.
#include "scene/buffers.h"

namespace glint {

const char* bufferName(Buffer buffer) {
  switch (buffer) {
    case Buffer::Render: return "render";
    case Buffer::Diffuse: return "diffuse";
    case Buffer::Specular: return "specular";
    case Buffer::Depth: return "depth";
    case Buffer::Normal: return "normal";
    case Buffer::Roughness: return "roughness";
    case Buffer::F0: return "f0";
  }
  return "unknown";
}

std::optional<Buffer> bufferFromName(const std::string& name) {
  for (Buffer b : kAllBuffers)
    if (name == bufferName(b)) return b;
  return std::nullopt;
}

int bufferChannels(Buffer buffer) { return buffer == Buffer::Depth || buffer == Buffer::Roughness ? 1 : 3; }

bool isRadianceBuffer(Buffer buffer) {
  return buffer == Buffer::Render || buffer == Buffer::Diffuse || buffer == Buffer::Specular;
}

ViewBuffers ViewBuffers::allocate(int width, int height) {
  ViewBuffers view;
  for (Buffer b : kAllBuffers) view[b] = Image(width, height, bufferChannels(b));
  return view;
}

}  // namespace glint
