// Replays fuzz inputs without libFuzzer (scripts/fuzz.sh): every file named on the command line,
// and every regular file under every folder named there (sorted, so runs print alike), is
// read whole and handed to the target's LLVMFuzzerTestOneInput once. This is how the
// regression corpus tests/fuzz_corpus/<name>/ runs under the normal build (ctest
// fuzz_replay_<name>). A finding shows as it does under libFuzzer: an exception escaping
// the target or a crash ends the process with a non-zero status, after the input's name
// has been printed.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> InputFiles(int argc, char** argv) {
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    if (!fs::is_directory(arg)) {
      files.push_back(arg);
      continue;
    }
    std::vector<fs::path> in_dir;
    for (const auto& entry : fs::recursive_directory_iterator(arg)) {
      if (entry.is_regular_file()) in_dir.push_back(entry.path());
    }
    std::sort(in_dir.begin(), in_dir.end());
    files.insert(files.end(), in_dir.begin(), in_dir.end());
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: " << argv[0] << " FILE_OR_FOLDER...\n";
    return 2;
  }
  const std::vector<fs::path> files = InputFiles(argc, argv);
  if (files.empty()) {
    std::cerr << argv[0] << ": no inputs found\n";
    return 2;
  }
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
      std::cerr << argv[0] << ": cannot read " << file.string() << "\n";
      return 2;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::cout << "replay " << file.string() << " (" << bytes.size() << " bytes)" << std::endl;
    try {
      LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    } catch (const std::exception& e) {
      std::cerr << "FINDING: " << file.string() << ": uncaught exception: " << e.what() << "\n";
      return 1;
    }
  }
  std::cout << files.size() << " inputs replayed\n";
  return 0;
}
