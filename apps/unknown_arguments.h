// Unknown subcommands and options answered with the closest valid one, before CLI11
// parses (CLI11 alone says "A subcommand is required" to `trackbed runn`).
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// The first argument of argv that `app` does not know — a subcommand, or an option
/// of the subcommand given (`--name` or `--name=value`, `-n`) — as the line to answer
/// it with: "trackbed: unknown subcommand 'runn'; did you mean 'run'?", "trackbed run:
/// unknown option '--seeed'; did you mean '--seed'?" (without a close one, the valid
/// ones listed); nullopt when every argument is known. An option's value, anything
/// after "--" and a subcommand's positional arguments are not checked.
std::optional<std::string> UnknownArgument(CLI::App& app, int argc, const char* const* argv);

}  // namespace trackbed::apps
