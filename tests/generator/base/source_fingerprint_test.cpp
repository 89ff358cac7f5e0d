// The build's source fingerprint (base/source_fingerprint.h), which batch fingerprints include.
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "base/source_fingerprint.h"

namespace cutaway {
namespace {

TEST(SourceFingerprint, IsTheSha256OfSomeSources) {
  const std::string f = source_fingerprint();
  ASSERT_EQ(f.size(), 64u);
  EXPECT_EQ(f.find_first_not_of("0123456789abcdef"), std::string::npos) << f;
  // Not the hash of an empty listing (no sources found).
  EXPECT_NE(f, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

}  // namespace
}  // namespace cutaway
