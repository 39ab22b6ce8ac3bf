// The example in docs/writing-a-pass.md's "Unit-testing your pipeline" is
// quoted from the plugin template, whose test the install chain builds and
// runs (plugin.template_unit_test): every line of each code block there must
// be a line of the template's test or CMakeLists.txt, so the doc cannot
// drift into code that does not compile.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::set<std::string> linesOf(const std::string& text) {
  std::set<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.insert(line);
  return out;
}

}  // namespace

TEST(TestingDocs, ExampleIsQuotedFromTheTemplate) {
  const std::string src = RGRAPH_SOURCE_DIR;
  const std::string doc = readText(src + "/docs/writing-a-pass.md");
  const size_t begin = doc.find("## Unit-testing your pipeline");
  ASSERT_NE(begin, std::string::npos) << "docs/writing-a-pass.md lost its section \"Unit-testing your pipeline\"";
  const size_t end = doc.find("\n## ", begin + 1);
  const std::string section = doc.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  const std::set<std::string> cpp = linesOf(readText(src + "/examples/plugin-template/test_vignette_pipeline.cpp"));
  const std::set<std::string> cmake = linesOf(readText(src + "/examples/plugin-template/CMakeLists.txt"));

  size_t blocks = 0, pos = 0;
  while ((pos = section.find("```", pos)) != std::string::npos) {
    const size_t langEnd = section.find('\n', pos);
    const size_t close = section.find("\n```", langEnd);
    ASSERT_NE(close, std::string::npos) << "unclosed code block";
    const std::string lang = section.substr(pos + 3, langEnd - pos - 3);
    const std::set<std::string>& from = lang == "cmake" ? cmake : cpp;
    ASSERT_TRUE(lang == "cpp" || lang == "cmake") << "code block of language '" << lang << "'";
    std::istringstream in(section.substr(langEnd + 1, close - langEnd - 1));
    for (std::string line; std::getline(in, line);)
      EXPECT_TRUE(from.count(line)) << "docs/writing-a-pass.md quotes a line the template's " << lang
                                    << " does not have:\n"
                                    << line;
    ++blocks;
    pos = close + 4;
  }
  EXPECT_EQ(blocks, 3u);  // compileVignette and a test, an in-process type's test, CMakeLists.txt
}
