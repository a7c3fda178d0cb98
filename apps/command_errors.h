// How every `trackbed` subcommand ends: its errors on stderr with exit status 2.
#pragma once

#include <exception>
#include <functional>
#include <iostream>

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// Runs a subcommand's body from its CLI11 callback. An exception prints "trackbed
/// NAME: what" on stderr (after what stdout holds) and exits with status 2; otherwise
/// the command exits with status 0.
inline void RunCommand(const char* name, const std::function<void()>& body) {
  try {
    body();
    std::cout.flush();
  } catch (const std::exception& e) {
    std::cout.flush();
    std::cerr << "trackbed " << name << ": " << e.what() << std::endl;
    throw CLI::RuntimeError(2);
  }
  throw CLI::Success();
}

}  // namespace trackbed::apps
