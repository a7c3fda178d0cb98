// Run-folder file writing (see log_file.h).
#include "trackbed/runner/log_file.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace trackbed::runner {

namespace fs = std::filesystem;

void WriteAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::out | std::ios::trunc);
    f << text;
    f.close();
    if (!f) throw std::runtime_error(tmp.string() + ": cannot write: " + std::strerror(errno));
  }
  fs::rename(tmp, path);
}

}  // namespace trackbed::runner
