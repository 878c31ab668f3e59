// The strength rule for a token an operator chooses (`avk serve --token`): long enough, varied,
// and neither a repeated part nor a run of steps, whatever alphabet it is written in.
#include <gtest/gtest.h>

#include <string>

#include "server/token_strength.hpp"

namespace {

using avk::server::token_entropy_bits;
using avk::server::token_weakness;

// Regression: 0123456789abcdef0123456789abcdef scored 128 bits by its characters' frequencies
// (16 characters, each twice) and was accepted.
TEST(TokenStrength, SequentialAndRepetitiveTokensAreRefused) {
  for (const std::string token : {
           "0123456789abcdef0123456789abcdef",          // ascending, twice
           "fedcba9876543210fedcba9876543210",          // descending, twice
           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJ",      // ascending, 36 different characters
           "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcd",  // ascending across digits and letters
           "acegikmoqsuwyACEGIKMOQSUWY0246813579",      // a step of 2
           "Xy7Qp2Lm9Rt4Wz8KXy7Qp2Lm9Rt4Wz8K",          // a random-looking half said twice
           "aabbccddeeffgghhiijjkkllmmnnoopp",          // pairs, ascending
           "ab1ab1ab1ab1ab1ab1ab1ab1ab1ab1ab1ab1",      // few characters
       }) {
    const auto why = token_weakness(token);
    EXPECT_TRUE(why) << token << " (" << token_entropy_bits(token) << " bits) was accepted";
  }
  // The step rule names what it found.
  const auto why = token_weakness("0123456789abcdef0123456789abcdef");
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("too predictable"), std::string::npos) << *why;
}

TEST(TokenStrength, FewDifferentCharactersAreRefusedNamingTheCount) {
  // 40 characters over 8 different ones.
  const auto why = token_weakness("13579bdf31975fdb57913dbf79135fbd9735bfd1");
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("only 8 different characters"), std::string::npos) << *why;
}

TEST(TokenStrength, ShortOrUnsafeTokensAreRefusedAsBefore) {
  EXPECT_NE(token_weakness(std::string(16, 'a'))->find("at least 32 characters"),
            std::string::npos);
  EXPECT_NE(
      token_weakness(std::string("08477f97dd83dc8b5695b1e65081ccb5 x"))->find("may hold only"),
      std::string::npos);
  EXPECT_TRUE(token_weakness(std::string(64, 'a')));
}

// Tokens drawn at random (openssl rand -hex 16, -base64 32) pass, as do the tests' own.
TEST(TokenStrength, RandomTokensPass) {
  for (const std::string token :
       {"08477f97dd83dc8b5695b1e65081ccb5", "aaf6e100ebfdfb2312cfdd91d0ccfccf",
        "c1fed68b8cb429fe13171d87ba9afc35", "ef72bc2518f0d0821661d7d6f5d71237",
        "KC9Q2G5ehwXZDc3oBnE-DjGjgfresfaWFEkYCvNo0x8",
        "map-tiles-token-0123456789-abcdefghijKLMN"}) {
    EXPECT_FALSE(token_weakness(token)) << token << ": " << *token_weakness(token);
    EXPECT_GE(token_entropy_bits(token), 96.0) << token;
  }
}

}  // namespace
