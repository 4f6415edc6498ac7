#include "campo/json_reader.hpp"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& text) {
  try {
    parse_json_text(text, "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(JsonReader, BuildsTheSameDocumentAsNlohmann) {
  const std::string text =
      R"({"a": [1, -2, 3.5, 18446744073709551615, "s", true, null, {"b": {}}, []], "c": {"d": [[]]}})";
  EXPECT_EQ(parse_json_text(text, "in.json"), nlohmann::json::parse(text));
  EXPECT_EQ(parse_json_text("7", "in.json"), nlohmann::json(7));
}

TEST(JsonReader, DuplicateKeysNameBothPlaces) {
  // Line 2 holds both keys; their opening quotes are at columns 3 and 21.
  const std::string error = error_of("{\"objects\": [\n {\"type\": \"cuboid\", \"type\": \"plane\"}]}");
  EXPECT_THAT(error, HasSubstr("in.json: /objects/0/type: duplicate key \"type\" at line 2, column 21; "
                               "first at line 2, column 3"));
  // The same key in different objects is fine.
  EXPECT_EQ(error_of(R"([{"a": 1}, {"a": 2}, {"b": {"a": 3}}])"), "no error");
}

TEST(JsonReader, NumberOverflowIsAnInputErrorWithItsPointer) {
  EXPECT_THAT(error_of(R"({"world": {"seed": 1, "time_limit_s": 1e999}})"),
              HasSubstr("in.json: /world/time_limit_s: number out of range at line 1, column 39: "
                        "expected a finite number (magnitude below 1.8e308), got 1e999 (5 characters)"));
  EXPECT_THAT(error_of(R"({"path": [[0, 0], [1, -1e400]]})"), HasSubstr("/path/1/1: number out of range"));
  const std::string huge(100000, '9');
  const std::string error = error_of("{\"a\": [" + huge + "]}");
  EXPECT_THAT(error, HasSubstr("/a/0: number out of range"));
  EXPECT_THAT(error, HasSubstr("(100000 characters)"));
  EXPECT_LT(error.size(), 300u);
}

TEST(JsonReader, NulInsideAStringIsRefused) {
  EXPECT_THAT(error_of(R"({"csv": "terrain.csv\u0000.png"})"),
              HasSubstr("in.json: /csv: expected text without NUL characters"));
  EXPECT_THAT(error_of(R"({"a": {"k\u0000": 1}})"), HasSubstr("in.json: /a: expected text without NUL"));
}

TEST(JsonReader, DepthAndSyntaxErrors) {
  EXPECT_THAT(error_of(std::string(33, '[') + std::string(33, ']')), HasSubstr("nesting deeper than 32 levels"));
  EXPECT_EQ(error_of(std::string(32, '[') + std::string(32, ']')), "no error");
  EXPECT_THAT(error_of("{\n \"a\": [1,]\n}"), HasSubstr("in.json: invalid JSON at line 2, column 10"));
}

}  // namespace
}  // namespace campo
