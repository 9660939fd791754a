// Fuzz harness for edit files (edit/edit_file.cpp), each accepted file also applied to a
// small scene, since the selections and operations it declares are only exercised there.
#include <cstddef>
#include <cstdint>

#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return glint::fuzz::parseAsFile(data, size, "edits", ".json", [](const auto& path) {
    glint::EditDocument document = glint::readEditFile(path);
    glint::GaussianScene scene = glint::fuzz::smallScene();
    glint::applyEdits(document, scene);
    glint::editDocumentToJson(document);
  });
}
