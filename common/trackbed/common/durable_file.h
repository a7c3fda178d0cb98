// Files that survive a crash and a power loss: written whole or not at all, and on
// disk before anyone can see them. Every file that marks work as finished (a run's
// metrics.json, a sweep's cell records and summaries) is written this way.
#pragma once

#include <filesystem>
#include <string>

namespace trackbed {

/// Writes `text` to `path` through a temporary file that is synced to disk, renamed
/// over `path`, and the folder synced: after a crash or power loss `path` holds the
/// old contents or the whole new ones. Throws std::runtime_error naming the file.
void WriteFileAtomically(const std::filesystem::path& path, const std::string& text);

/// Syncs every regular file under `dir` (recursively) and every folder to disk, so
/// that a file written after this one can only be seen with all of these. Files that
/// vanish meanwhile are skipped; throws std::runtime_error naming a file that cannot
/// be synced.
void SyncFolder(const std::filesystem::path& dir);

}  // namespace trackbed
