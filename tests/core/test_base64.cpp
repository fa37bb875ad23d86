#include <gtest/gtest.h>

#include "core/base64.hpp"

using namespace forensim;

TEST(Base64, EncodeMatchesRfc4648Vectors) {
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\x00\x10", 3)), "/wAQ");
}

TEST(Base64, DecodeInvertsEncodeAndRejectsBadText) {
  std::string all;
  for (int i = 0; i < 256; ++i) all += static_cast<char>(i);
  for (std::size_t n = 0; n < all.size(); n += 7) {
    const std::string bytes = all.substr(0, n);
    std::size_t bad = 0;
    const auto decoded = base64_decode(base64_encode(bytes), bad);
    ASSERT_TRUE(decoded.has_value()) << n;
    EXPECT_EQ(*decoded, bytes);
    EXPECT_EQ(base64_encode(bytes).size(), base64_length(n));
  }
  std::size_t bad = 0;
  EXPECT_FALSE(base64_decode("Zm9v!mFy", bad).has_value());
  EXPECT_EQ(bad, 4u);
  EXPECT_FALSE(base64_decode("Zm9", bad).has_value());
}
