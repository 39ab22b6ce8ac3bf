#include <GL/glcorearb.h>

#include "gl_test_util.h"
#include "rgraph/error.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {
std::string compileError(ShaderLibrary& lib, const std::string& vert, const std::string& frag) {
  try {
    lib.program(vert, frag);
  } catch (const RuntimeError& e) {
    return e.what();
  }
  return {};
}
}  // namespace

TEST_F(GlTest, ProgramsAreCompiledOnceAndCached) {
  uint32_t a = shaders->program("fullscreen.vert", "gradient.frag");
  EXPECT_NE(a, 0u);
  EXPECT_TRUE(glIsProgram(a));
  EXPECT_EQ(shaders->program("fullscreen.vert", "gradient.frag"), a);
  EXPECT_EQ(shaders->cachedPrograms(), 1u);
  uint32_t b = shaders->program("fullscreen.vert", "gradient.frag", {"SOMETHING=1"});
  EXPECT_NE(a, b);
  EXPECT_EQ(shaders->cachedPrograms(), 2u);
}

TEST_F(GlTest, ResolveFindsBuiltInAndTestShaders) {
  EXPECT_NE(shaders->resolve("fullscreen.vert").find("fullscreen.vert"), std::string::npos);
  EXPECT_NE(shaders->resolve("mrt.frag").find("tests/gl/shaders"), std::string::npos);
  try {
    shaders->resolve("no_such_shader.frag");
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_shader.frag"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("searched"), std::string::npos) << e.what();
  }
}

TEST_F(GlTest, SyntaxErrorNamesFileAndLine) {
  std::string msg = compileError(*shaders, "fullscreen.vert", "bad_syntax.frag");
  ASSERT_FALSE(msg.empty());
  EXPECT_NE(msg.find("bad_syntax.frag:7:"), std::string::npos) << msg;
  EXPECT_EQ(shaders->cachedPrograms(), 0u);
}

TEST_F(GlTest, SemanticErrorNamesFileAndLine) {
  std::string msg = compileError(*shaders, "fullscreen.vert", "undeclared.frag");
  EXPECT_NE(msg.find("undeclared.frag:6:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("undeclared_thing"), std::string::npos) << msg;
}

TEST_F(GlTest, ErrorInIncludedFileNamesTheIncludedFile) {
  std::string msg = compileError(*shaders, "fullscreen.vert", "include_bad.frag");
  EXPECT_NE(msg.find("common_bad.glsl:3:"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("include_bad.frag:3:"), std::string::npos) << msg;
}

TEST_F(GlTest, LineNumbersSurviveDefines) {
  try {
    shaders->program("fullscreen.vert", "bad_syntax.frag", {"A", "B=2", "C"});
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    std::string msg = e.what();
    EXPECT_EQ(msg.find("bad_syntax.frag:7:"), msg.find("bad_syntax.frag")) << msg;
    EXPECT_NE(msg.find("bad_syntax.frag:7:"), std::string::npos) << msg;
  }
}

TEST_F(GlTest, DefinesAreInsertedAfterVersionAndLinesStayRight) {
  std::string src = shaders->preprocess("include_ok.frag", {"DOUBLE", "SCALE=2.0"});
  EXPECT_EQ(src.rfind("#version 450 core\n#define DOUBLE\n#define SCALE 2.0\n", 0), 0u) << src;
  EXPECT_NE(shaders->program("fullscreen.vert", "include_ok.frag", {"DOUBLE"}), 0u);
  EXPECT_NE(shaders->program("fullscreen.vert", "include_ok.frag"), 0u);
}

TEST_F(GlTest, LinkErrorThrows) {
  std::string msg = compileError(*shaders, "fullscreen.vert", "link_error.frag");
  EXPECT_NE(msg.find("link"), std::string::npos) << msg;
  EXPECT_NE(msg.find("link_error.frag"), std::string::npos) << msg;
}

TEST_F(GlTest, MissingShaderFileThrows) {
  std::string msg = compileError(*shaders, "fullscreen.vert", "does_not_exist.frag");
  EXPECT_NE(msg.find("does_not_exist.frag"), std::string::npos) << msg;
}
