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

/// For tests: called with each durable step, in order — "sync" (a file or folder on
/// disk) and "rename" (the temporary file made visible; `path` is the target) — since
/// a power loss itself cannot be tested. Null (the default): none. Not thread-safe.
using DurableStepHook = void (*)(const char* step, const std::filesystem::path& path);
void SetDurableStepHookForTesting(DurableStepHook hook);

/// For tests of what a crash leaves: with TRACKBED_TEST_KILL_AT=POINT:SUFFIX in the
/// environment, the process kills itself with SIGKILL (as a crash or `kill -9` would,
/// nothing flushed or cleaned up) when WriteFileAtomically reaches POINT —
/// `before_rename` (the temporary file complete and synced, the target not yet
/// replaced) or `after_rename` (replaced, its folder not yet synced) — for a target
/// whose path ends in SUFFIX. Unset (normal use): nothing.
inline constexpr const char* kKillAtVariable = "TRACKBED_TEST_KILL_AT";

}  // namespace trackbed
