// The Frame block's two declarations held together member by member: the
// std140 block in shaders/include/frame.glsl, as glslang reflects it, against
// the C++ FrameBlock that GpuScene uploads (core/src/gl/frame_block.h). A
// member moved or retyped on either side fails here; a size check alone does
// not see two members of one size swapped.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_block.h"
#include "rgraph/shader_check.h"

using namespace rgraph;

namespace {

const std::string kTestShaders = std::string(RGRAPH_TEST_DATA_DIR) + "/shadercheck/shaders";

// The shipped shaders only (not an installed or built copy), after the test's own.
std::vector<std::string> dirs() { return {kTestShaders, std::string(RGRAPH_SOURCE_DIR) + "/shaders"}; }

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += s + "\n";
  return out;
}

// Every difference between the reflected block and the C++ table, one line each.
std::vector<std::string> mismatches(const UniformBlock& glsl, const std::vector<detail::FrameBlockMember>& cpp,
                                    size_t cppSize) {
  std::vector<std::string> out;
  if (glsl.size != static_cast<int>(cppSize))
    out.push_back("block size: " + std::to_string(glsl.size) + " in GLSL, " + std::to_string(cppSize) + " in C++");
  for (const auto& m : cpp) {
    const std::string name(m.glslName);
    const UniformBlockMember* g = glsl.findMember(name);
    if (!g) {
      out.push_back(name + ": in FrameBlock, not in the GLSL block");
      continue;
    }
    if (g->offset != static_cast<int>(m.offset))
      out.push_back(name + ": offset " + std::to_string(g->offset) + " in GLSL, " + std::to_string(m.offset) +
                    " in C++");
    if (g->type != m.glslType) out.push_back(name + ": type " + g->type + " in GLSL, " + std::string(m.glslType) + " in C++");
  }
  for (const auto& g : glsl.members) {
    bool listed = false;
    for (const auto& m : cpp) listed = listed || m.glslName == g.name;
    if (!listed) out.push_back(g.name + ": in the GLSL block, not in FrameBlock (kFrameBlockMembers)");
  }
  return out;
}

std::vector<detail::FrameBlockMember> cppMembers() {
  return {std::begin(detail::kFrameBlockMembers), std::end(detail::kFrameBlockMembers)};
}

const UniformBlock& frameBlockOf(ShaderChecker& checker, const std::string& comp) {
  ShaderProgramSpec spec;
  spec.comp = comp;
  const ProgramCheck& pc = checker.program(spec);
  EXPECT_TRUE(pc.ok) << (pc.messages.empty() ? std::string() : pc.messages.front().text);
  const UniformBlock* block = pc.findUniformBlock("Frame");
  if (!block) throw std::runtime_error(comp + ": no uniform block 'Frame' reflected");
  return *block;
}

TEST(FrameBlockLayout, EveryMemberOfFrameGlslHasTheOffsetAndTypeOfFrameBlock) {
  ShaderChecker checker(dirs());
  const UniformBlock& frame = frameBlockOf(checker, "frame_reader.comp");
  EXPECT_EQ(frame.binding, 0);
  // Every member is reflected, read or not (u_cameraPos only is read).
  EXPECT_EQ(frame.members.size(), std::size(detail::kFrameBlockMembers));
  const std::vector<std::string> diff = mismatches(frame, cppMembers(), sizeof(detail::FrameBlock));
  EXPECT_TRUE(diff.empty()) << joined(diff);
}

// The comparison sees a change on the GLSL side: two members of one size
// swapped (same block size) and a member retyped.
TEST(FrameBlockLayout, MembersSwappedOrRetypedInTheGlslBlockAreNamed) {
  ShaderChecker checker(dirs());
  const std::string diff = joined(mismatches(frameBlockOf(checker, "frame_swapped.comp"), cppMembers(),
                                             sizeof(detail::FrameBlock)));
  EXPECT_NE(diff.find("u_view: offset 64 in GLSL, 0 in C++"), std::string::npos) << diff;
  EXPECT_NE(diff.find("u_proj: offset 0 in GLSL, 64 in C++"), std::string::npos) << diff;
  EXPECT_NE(diff.find("u_counts: type vec4 in GLSL, ivec4 in C++"), std::string::npos) << diff;
  EXPECT_EQ(diff.find("block size"), std::string::npos) << diff;
  EXPECT_EQ(diff.find("u_jitter"), std::string::npos) << diff;
}

// ... and on the C++ side: the table is made from FrameBlock's own offsets and
// types (offsetof, decltype), so a member moved or retyped there changes it.
TEST(FrameBlockLayout, MembersMovedOrRetypedInTheCppTableAreNamed) {
  ShaderChecker checker(dirs());
  std::vector<detail::FrameBlockMember> cpp = cppMembers();
  std::swap(cpp[0].offset, cpp[1].offset);  // view and proj swapped in the struct
  cpp[14].glslType = detail::glslTypeOf<glm::vec4>();  // frame: ivec4 -> vec4
  const std::string diff =
      joined(mismatches(frameBlockOf(checker, "frame_reader.comp"), cpp, sizeof(detail::FrameBlock) + 16));
  EXPECT_NE(diff.find("u_view: offset 0 in GLSL, 64 in C++"), std::string::npos) << diff;
  EXPECT_NE(diff.find("u_frame: type ivec4 in GLSL, vec4 in C++"), std::string::npos) << diff;
  EXPECT_NE(diff.find("block size: 576 in GLSL, 592 in C++"), std::string::npos) << diff;
  cpp.pop_back();
  EXPECT_NE(joined(mismatches(frameBlockOf(checker, "frame_reader.comp"), cpp, sizeof(detail::FrameBlock)))
                .find("u_frame: in the GLSL block, not in FrameBlock"),
            std::string::npos);
}

}  // namespace
