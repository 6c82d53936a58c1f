// The operator token: long, random, and matched only by itself.
#include "rpsd/monitor/access_token.h"

#include <gtest/gtest.h>

#include <cctype>

namespace rpsd::monitor {
namespace {

TEST(AccessToken, IsThirtyTwoHexDigitsAndNewEachTime) {
  const std::string a = draw_access_token(), b = draw_access_token();
  ASSERT_EQ(a.size(), 32u);
  for (const char ch : a) EXPECT_TRUE(std::isxdigit(static_cast<unsigned char>(ch))) << a;
  EXPECT_NE(a, b);
}

TEST(AccessToken, OnlyTheSameTextMatches) {
  const std::string token = "0123456789abcdef0123456789abcdef";
  EXPECT_TRUE(token_matches(token, token));
  EXPECT_FALSE(token_matches(token, ""));
  EXPECT_FALSE(token_matches(token, token.substr(0, 31)));
  EXPECT_FALSE(token_matches(token, token + "0"));
  EXPECT_FALSE(token_matches(token, "0123456789abcdef0123456789abcdee"));
  EXPECT_FALSE(token_matches("", ""));  // a monitor without a token accepts no command
}

}  // namespace
}  // namespace rpsd::monitor
