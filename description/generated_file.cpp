// Generated files written once (see generated_file.h).
#include "generated_file.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <system_error>

#include "trackbed/description/description_error.h"

namespace trackbed::description {

namespace fs = std::filesystem;

void WriteGeneratedFile(const fs::path& file, const std::string& text, const std::string& what) {
  if (fs::is_regular_file(file)) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream held;
    held << in.rdbuf();
    if (held.str() == text) return;
  }
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  const fs::path tmp = file.string() + "." + std::to_string(::getpid()) + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw DescriptionError(tmp.string() + ": cannot write " + what);
  }
  fs::rename(tmp, file, ec);
  if (ec) throw DescriptionError(file.string() + ": cannot write: " + ec.message());
}

}  // namespace trackbed::description
