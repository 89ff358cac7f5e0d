// The CRC-32 that checks cut cache entries: the standard check value and chaining.
#include "base/hash.h"

#include <string>

#include <gtest/gtest.h>

namespace cutaway {
namespace {

// CRC-32/ISO-HDLC's check value (the CRC of the nine digits), as zlib, PNG and gzip give it.
TEST(Hash, Crc32GivesTheStandardCheckValue) {
  EXPECT_EQ(crc32(""), 0u);
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);
  EXPECT_NE(crc32(std::string("a\0b", 3)), crc32("ab"));  // every byte counts, NUL too
}

// Bytes checked in parts give the CRC of the whole (a cut cache entry: payload, then trailer).
TEST(Hash, Crc32OfPartsInTurnIsTheCrc32OfTheWhole) {
  const std::string whole = "a cut cache entry: its payload, then its trailer";
  for (size_t split = 0; split <= whole.size(); ++split)
    EXPECT_EQ(crc32(whole.substr(split), crc32(whole.substr(0, split))), crc32(whole)) << split;
}

}  // namespace
}  // namespace cutaway
