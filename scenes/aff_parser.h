#pragma once
// Reads an AFF scene (BART) and the files it includes into an AffDocument. Includes (`i detail
// file`) are relative to the including file; the fill material (`fm`, `f`) is a state that holds
// for the shapes after it, across files, as in BART's reference parser.
#include <filesystem>

#include "scenes/aff_document.h"

namespace kinray {

/// Parses `file` and its includes. Throws InputError "file:line: problem" for the first problem.
/// A texture file that does not exist is a warning (AffDocument::warnings): the shapes that name
/// it keep the colour of their material.
[[nodiscard]] AffDocument parse_aff(const std::filesystem::path& file);

}  // namespace kinray
