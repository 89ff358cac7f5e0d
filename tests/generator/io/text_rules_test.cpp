// The command line's seed rule (io/text_rules.h): whole numbers 0..2^63-1 in decimal digits,
// every other text refused with the rule in words.
#include <gtest/gtest.h>

#include "io/text_rules.h"

namespace cutaway {
namespace {

TEST(TextRules, SeedsAreWholeNumbersUpTo2To63) {
  EXPECT_EQ(*parse_seed("0"), 0u);
  EXPECT_EQ(*parse_seed("42"), 42u);
  EXPECT_EQ(*parse_seed("007"), 7u);
  EXPECT_EQ(*parse_seed("9223372036854775807"), kMaxSeed);
  for (const char* bad : {"", "-5", "+5", " 5", "5 ", "1e3", "0x10", "4.0", "9223372036854775808",
                          "18446744073709551615", "99999999999999999999999", "seven"}) {
    const Outcome<uint64_t> r = parse_seed(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_EQ(r.reason().find("must be a whole number from 0 to 9223372036854775807"), 0u)
        << r.reason();
  }
}

}  // namespace
}  // namespace cutaway
