// The public headers (include/campo/, installed with libcampo) include only
// the standard library, Eigen, nlohmann_json and each other: what the installed
// CMake package's find_dependency provides. Bullet, Embree, OSMesa, OpenCV and
// the other private dependencies stay inside libcampo.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

// Every #include of the public headers in the source tree (version.hpp as its template).
std::vector<std::pair<std::string, std::string>> public_includes() {
  std::vector<std::pair<std::string, std::string>> includes;  // (header, included)
  const std::regex include(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  for (const auto& entry : fs::directory_iterator(fs::path(CAMPO_SOURCE_DIR) / "include" / "campo")) {
    const std::string name = entry.path().filename().string();
    if (!name.ends_with(".hpp") && !name.ends_with(".hpp.in")) continue;
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, include)) includes.emplace_back(name, m[1].str() + m[2].str());
    }
  }
  return includes;
}

TEST(PublicHeaders, IncludeOnlyTheStandardLibraryEigenJsonAndEachOther) {
  const auto includes = public_includes();
  ASSERT_GT(includes.size(), 20u);  // the scan found the headers
  std::set<std::string> public_headers;
  for (const auto& entry : fs::directory_iterator(fs::path(CAMPO_SOURCE_DIR) / "include" / "campo")) {
    std::string name = entry.path().filename().string();
    if (name.ends_with(".in")) name.resize(name.size() - 3);
    public_headers.insert("campo/" + name);
  }
  const std::regex standard(R"(<[a-z_]+>)");  // <vector>, <string_view>, <cstdint> ...
  for (const auto& [header, included] : includes) {
    const std::string path = included.substr(1);
    const bool allowed = (included[0] == '"' && public_headers.contains(path)) ||
                         (included[0] == '<' && (std::regex_match(included + ">", standard) ||
                                                 path.starts_with("Eigen/") || path.starts_with("nlohmann/")));
    EXPECT_TRUE(allowed) << "include/campo/" << header << " includes " << included
                         << ": a public header may include only the standard library, <Eigen/...>, "
                            "<nlohmann/...> and other public headers (\"campo/...\")";
  }
}

TEST(PublicHeaders, NoneNamesAPrivateDependency) {
  // Caught by the rule above too; said here by name, as the installed package promises.
  for (const auto& [header, included] : public_includes()) {
    for (const char* dependency : {"btBullet", "Bullet", "LinearMath", "embree", "rtcore", "GL/", "osmesa", "opencv",
                                   "cv.h", "octomap", "nanoflann", "muParser", "openssl", "CLI/"}) {
      EXPECT_EQ(included.find(dependency), std::string::npos) << "include/campo/" << header << " includes " << included;
    }
  }
}

}  // namespace
