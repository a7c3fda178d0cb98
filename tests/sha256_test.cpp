// SHA-256 against the examples of FIPS 180-2 (appendix B) and a file's bytes.
#include "trackbed/common/sha256.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace trackbed {
namespace {

std::string Digest(const std::string& bytes, std::size_t piece) {
  Sha256 sha;
  for (std::size_t k = 0; k < bytes.size(); k += piece) {
    sha.Add(bytes.data() + k, std::min(piece, bytes.size() - k));
  }
  return sha.HexDigest();
}

TEST(Sha256Test, MatchesTheStandardsExamplesInAnyPieces) {
  const std::string two_blocks = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  for (const std::size_t piece : {1, 7, 64, 1000}) {
    EXPECT_EQ(Digest("", piece),
              "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(Digest("abc", piece),
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(Digest(two_blocks, piece),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  }
  EXPECT_EQ(Digest(std::string(1000000, 'a'), 4096),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256Test, OfAFileIsOfItsBytes) {
  const std::filesystem::path file = std::filesystem::path(testing::TempDir()) / "sha256_abc";
  std::ofstream(file, std::ios::binary) << "abc";
  EXPECT_EQ(Sha256OfFile(file), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_THROW(Sha256OfFile(file.string() + "_missing"), std::runtime_error);
}

}  // namespace
}  // namespace trackbed
