#pragma once
// The docs' tables of configuration fields are generated from the fields'
// declarations (ConfigFields::markdown). In a doc each stands between
//   <!-- fields NAME -->
// and
//   <!-- end fields -->
// expect_docs_tables() checks that every such block holds its generated table;
// with the environment variable CAMPO_UPDATE_DOCS=1 it writes them instead.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace campo::test_support {

inline constexpr const char* kFieldsEnd = "<!-- end fields -->";

inline std::string fields_begin(const std::string& name) { return "<!-- fields " + name + " -->"; }

/// Checks (or, with CAMPO_UPDATE_DOCS=1, rewrites) the tables of `doc`, a
/// path under the source tree, against `tables` (name -> generated table).
inline void expect_docs_tables(const std::string& doc, const std::map<std::string, std::string>& tables) {
  const std::filesystem::path path = std::filesystem::path(CAMPO_SOURCE_DIR) / doc;
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const char* update_env = std::getenv("CAMPO_UPDATE_DOCS");
  const bool update = update_env != nullptr && std::string(update_env) == "1";

  // Every block in the doc names a known table.
  std::set<std::string> found;
  for (std::size_t at = text.find("<!-- fields "); at != std::string::npos; at = text.find("<!-- fields ", at + 1)) {
    const std::size_t close = text.find(" -->", at);
    ASSERT_NE(close, std::string::npos) << doc << ": unterminated marker";
    const std::string name = text.substr(at + 12, close - at - 12);
    EXPECT_TRUE(tables.count(name)) << doc << " has a block of fields \"" << name << "\" that no declaration makes";
    found.insert(name);
  }
  for (const auto& [name, table] : tables) {
    ASSERT_TRUE(found.count(name)) << doc << " lacks the block " << fields_begin(name) << "; its table:\n" << table;
    const std::size_t begin = text.find(fields_begin(name)) + fields_begin(name).size() + 1;
    const std::size_t end = text.find(kFieldsEnd, begin);
    ASSERT_NE(end, std::string::npos) << doc << ": " << fields_begin(name) << " without " << kFieldsEnd;
    if (update) {
      text.replace(begin, end - begin, table);
    } else {
      EXPECT_EQ(text.substr(begin, end - begin), table)
          << doc << ": the table of " << name << " differs from its declarations; regenerate the docs' tables with "
          << "CAMPO_UPDATE_DOCS=1 and the test binary";
    }
  }
  if (update) std::ofstream(path) << text;
}

}  // namespace campo::test_support
