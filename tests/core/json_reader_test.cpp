#include "campo/json_reader.hpp"

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::HasSubstr;

std::string reader_error_of(const std::string& text) {
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
  const std::string error = reader_error_of("{\"objects\": [\n {\"type\": \"cuboid\", \"type\": \"plane\"}]}");
  EXPECT_THAT(error, HasSubstr("in.json: /objects/0/type: duplicate key \"type\" at line 2, column 21; "
                               "first at line 2, column 3"));
  // The same key in different objects is fine.
  EXPECT_EQ(reader_error_of(R"([{"a": 1}, {"a": 2}, {"b": {"a": 3}}])"), "no error");
}

TEST(JsonReader, NumberOverflowIsAnInputErrorWithItsPointer) {
  EXPECT_THAT(reader_error_of(R"({"world": {"seed": 1, "time_limit_s": 1e999}})"),
              HasSubstr("in.json: /world/time_limit_s: number out of range at line 1, column 39: "
                        "expected a finite number (magnitude below 1.8e308), got 1e999 (5 characters)"));
  EXPECT_THAT(reader_error_of(R"({"path": [[0, 0], [1, -1e400]]})"), HasSubstr("/path/1/1: number out of range"));
  const std::string huge(100000, '9');
  const std::string error = reader_error_of("{\"a\": [" + huge + "]}");
  EXPECT_THAT(error, HasSubstr("/a/0: number out of range"));
  EXPECT_THAT(error, HasSubstr("(100000 characters)"));
  EXPECT_LT(error.size(), 300u);
}

TEST(JsonReader, NulInsideAStringIsRefused) {
  EXPECT_THAT(reader_error_of(R"({"csv": "terrain.csv\u0000.png"})"),
              HasSubstr("in.json: /csv: expected text without NUL characters"));
  EXPECT_THAT(reader_error_of(R"({"a": {"k\u0000": 1}})"), HasSubstr("in.json: /a: expected text without NUL"));
}

TEST(JsonReader, DepthAndSyntaxErrors) {
  EXPECT_THAT(reader_error_of(std::string(33, '[') + std::string(33, ']')), HasSubstr("nesting deeper than 32 levels"));
  EXPECT_EQ(reader_error_of(std::string(32, '[') + std::string(32, ']')), "no error");
  EXPECT_THAT(reader_error_of("{\n \"a\": [1,]\n}"), HasSubstr("in.json: invalid JSON at line 2, column 10"));
}

TEST(JsonReader, PrintableEscapesControlCharactersAndKeepsUtf8) {
  using namespace std::string_literals;
  EXPECT_EQ(printable("a\0b"s), "a\\x00b");
  EXPECT_EQ(printable("\x1b[31mred"), "\\x1b[31mred");
  EXPECT_EQ(printable("line\r\nnext\tcell\x7f"), "line\\r\\nnext\\tcell\\x7f");
  // UTF-8 stays readable: 2, 3 and 4 byte characters.
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x9a\x81"), "caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x9a\x81");
  // C1 controls (U+0085, U+009B: a one-character CSI) are controls too.
  EXPECT_EQ(printable("a\xc2\x85" "b\xc2\x9b" "c"), "a\\u0085b\\u009bc");
  // Bytes that are not UTF-8: a lone continuation byte, a cut sequence, an overlong '/', a surrogate.
  EXPECT_EQ(printable("\x9b" "x"), "\\x9bx");
  EXPECT_EQ(printable("\xe2\x86"), "\\xe2\\x86");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");
  EXPECT_EQ(printable("plain text, [1, 2]: ~/x"), "plain text, [1, 2]: ~/x");
}

TEST(JsonReader, InputErrorsAreOneLineWithoutRawControlCharacters) {
  using namespace std::string_literals;
  const InputError e("maps/a\nb.map"s, "/objects/x\x1b"s, "got \"\0\r\"; caf\xc3\xa9"s);
  EXPECT_STREQ(e.what(), "maps/a\\nb.map: /objects/x\\x1b: got \"\\x00\\r\"; caf\xc3\xa9");
  EXPECT_EQ(e.file(), "maps/a\nb.map");  // the accessors keep the text as given
}

TEST(JsonReader, AnEmptyPathIsNamedAsOne) {
  EXPECT_STREQ(InputError("", "", "cannot read").what(), "\"\" (empty path): cannot read");
  try {
    read_text_file("");
    FAIL() << "an empty path was read";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "\"\" (empty path): expected the path of a file, got an empty string");
  }
}

TEST(JsonReader, ALoopOfSymbolicLinksGivesTheSystemsReason) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "campo_json_reader_loop";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::create_symlink("b.json", dir / "a.json");
  std::filesystem::create_symlink("a.json", dir / "b.json");
  try {
    read_json_file(dir / "a.json");
    FAIL() << "a loop of links was read";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("a.json: cannot read: Too many levels of symbolic links"));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace campo
