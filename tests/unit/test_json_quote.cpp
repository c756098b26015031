// common/json_quote: every JSON file mppm writes quotes its strings with it.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "common/json_quote.hpp"

namespace mppm {
namespace {

// JSON is YAML 1.2: a double-quoted JSON string read back by yaml-cpp is the original text. The
// text holds every character that must be escaped (the quote, the backslash, all 32 control
// characters), plain ASCII and multi-byte UTF-8 (kept as it is).
TEST(JsonQuote, ReadsBackAsTheTextForEveryCharacterThatNeedsAnEscape) {
  std::string text = "a \"quoted\" back\\slash, 9 \xC2\xB5m, ";
  for (int c = 1; c < 0x20; ++c) text += static_cast<char>(c);
  const std::string quoted = json_quote(text);
  for (const char c : quoted) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << "raw control character";
  EXPECT_EQ(YAML::Load(quoted).as<std::string>(), text);
}

TEST(JsonQuote, UsesTheShortEscapesAndFourHexDigitsForTheRest) {
  EXPECT_EQ(json_quote("\"\\\n\t\r"), "\"\\\"\\\\\\n\\t\\r\"");
  EXPECT_EQ(json_quote(std::string(1, '\x01')), "\"\\u0001\"");
  EXPECT_EQ(json_quote(std::string(1, '\x1f')), "\"\\u001f\"");
  EXPECT_EQ(json_quote(""), "\"\"");
}

}  // namespace
}  // namespace mppm
