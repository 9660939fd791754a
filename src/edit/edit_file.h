// Edit files (docs/edit-files.md) <-> EditDocument: reading with validation (one error naming
// the file and the JSON location of the problem), and atomic writing.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "edit/edit_document.h"

namespace glint {

// Reads and validates an edit file. Throws Error naming the file, e.g.
// `EDITS.json: operations[2]: unknown operation "rotat"`.
EditDocument readEditFile(const std::filesystem::path& path);

// Validates a parsed edit document; `source` names it in errors (usually the file path).
EditDocument parseEditDocument(const nlohmann::json& json, const std::string& source);

// The canonical JSON form: boxes as center / half_extent (rotation when not the identity),
// "everything" as a string unless it has filters. parseEditDocument reads it back exactly.
nlohmann::json editDocumentToJson(const EditDocument& document);

// The name of an operation in edit files ("translate", "rotate", ...).
const char* operationName(Operation::Kind kind);

// Writes the document atomically (pretty-printed JSON).
void writeEditFile(const std::filesystem::path& path, const EditDocument& document);

}  // namespace glint
