// Files the mapping writes for the renderer to read (unit shapes, textured shapes):
// written once, whole, and left alone while they hold the same text.
#pragma once

#include <filesystem>
#include <string>

namespace trackbed::description {

/// Writes `text` to `file` unless the file holds it already, through a temporary file
/// renamed into place, so that a reader (another run sharing the folder) never sees half
/// of it. Creates the file's folder. Throws DescriptionError naming the file, with
/// `what` saying what it was to hold, when it cannot write.
void WriteGeneratedFile(const std::filesystem::path& file, const std::string& text,
                        const std::string& what);

}  // namespace trackbed::description
