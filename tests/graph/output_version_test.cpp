// The output is one version: naming an intermediate version shows that
// version and culls the passes that only produce later ones. And what the
// output must be to be read back (single-sample colour texture within the
// texture size limit), and messages that name the version a slot binds.
#include <gtest/gtest.h>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;
using Strings = std::vector<std::string>;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// draw writes h, blur derives h_1, grade derives h_2; probe reads h_2.
GraphDesc chain(const std::string& output) {
  GraphDesc d;
  d.resources = {importedTex("h", false, Format::rgba16f), tex("side")};
  d.passes = {
      pass("draw", {wr("color", "h")}),
      pass("blur", {rmw("color", "h", "h_1")}),
      pass("grade", {rmw("color", "h_1", "h_2")}),
      pass("probe", {rd("src", "h_2"), wr("color", "side")}),
  };
  d.output = output;
  d.outputWhere = at(40, 13, "/output");
  return d;
}

const PlannedPass& planned(const Plan& plan, const std::string& name) {
  for (const auto& p : plan.passes)
    if (p.name == name) return p;
  static const PlannedPass none;
  ADD_FAILURE() << "no pass " << name;
  return none;
}

TEST(OutputVersion, IntermediateVersionIsTheImageAndLaterWritersAreCulled) {
  Plan plan = compile(chain("h_1"));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(plan.outputResource, ResourceIndex(0));
  EXPECT_EQ(plan.outputVersion, "h_1");
  EXPECT_EQ(orderNames(plan), (Strings{"draw", "blur"}));
  const PlannedPass& grade = planned(plan, "grade");
  EXPECT_TRUE(grade.culled);
  EXPECT_FALSE(grade.order.valid());
  EXPECT_EQ(grade.reason,
            "it writes 'h_2', a later version of 'h' than the output 'h_1', and nothing that reaches the output "
            "reads its outputs (h_2)");
  // A reader of the later version is culled for the ordinary reason.
  EXPECT_TRUE(planned(plan, "probe").culled);
  EXPECT_TRUE(contains(planned(plan, "probe").reason, "never read by a pass that reaches the output"))
      << planned(plan, "probe").reason;
  // h lives from draw to blur only.
  EXPECT_EQ(res(plan, "h").lastPass, StepIndex(1));
}

TEST(OutputVersion, ResourceNameIsItsFirstVersion) {
  Plan plan = compile(chain("h"));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(plan.outputVersion, "h");
  EXPECT_EQ(orderNames(plan), (Strings{"draw"}));
  EXPECT_TRUE(contains(planned(plan, "blur").reason, "a later version of 'h' than the output 'h'"));
}

TEST(OutputVersion, FinalVersionKeepsTheWholeChain) {
  Plan plan = compile(chain("h_2"));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(plan.outputVersion, "h_2");
  EXPECT_EQ(orderNames(plan), (Strings{"draw", "blur", "grade"}));
}

TEST(OutputVersion, DisabledWriterPassesTheEarlierVersionThrough) {
  GraphDesc d = chain("h_1");
  d.passes[1].enabled = false;
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(plan.outputVersion, "h");
  EXPECT_EQ(orderNames(plan), (Strings{"draw"}));
  EXPECT_EQ(planned(plan, "blur").reason, "disabled");
  EXPECT_TRUE(contains(planned(plan, "grade").reason, "'h_2', a later version of 'h'"));
}

TEST(OutputVersion, SideEffectPassOverwritingTheOutputIsAnError) {
  GraphDesc d = chain("h_1");
  d.passes[2].sideEffect = true;
  Plan plan = compile(d);
  auto found = withCode(plan, DiagCode::invalid_output);
  ASSERT_EQ(found.size(), 1u) << dumpDiagnostics(plan);
  EXPECT_EQ(found[0]->message,
            "output 'h_1' is overwritten by pass 'grade', which writes the later version 'h_2' and runs for its side "
            "effect; name 'h_2' as the output, or write the side effect's result to another resource");
  EXPECT_EQ(found[0]->where.line, 40);
  EXPECT_EQ(found[0]->pass, "grade");
}

TEST(OutputVersion, MultisampledDepthAndBufferOutputsAreRefusedAtTheOutput) {
  struct Case {
    ResourceDecl r;
    const char* part;
  } cases[] = {
      {tex("img", Format::rgba8, SizeSpec::output(), 1, 4), "is multisampled (4 samples) and cannot be read back"},
      {tex("img", Format::depth24), "has the depth format depth24; the output image must be a colour texture"},
      {buffer("img", 64), "is a buffer; the output image must be a texture"},
  };
  for (Case& c : cases) {
    SCOPED_TRACE(c.part);
    GraphDesc d;
    c.r.imported = true;
    c.r.importedHasContent = false;
    d.resources = {c.r};
    const Access a = c.r.kind == ResourceKind::buffer       ? Access::storage_write
                     : c.r.texture.format == Format::depth24 ? Access::depth_attachment
                                                              : Access::color_attachment;
    d.passes = {pass("draw", {wr("out", "img", a)})};
    d.output = "img";
    d.outputWhere = at(9, 13, "/output");
    Plan plan = compile(d);
    auto found = withCode(plan, DiagCode::invalid_output);
    ASSERT_EQ(found.size(), 1u) << dumpDiagnostics(plan);
    EXPECT_TRUE(contains(found[0]->message, c.part)) << found[0]->message;
    EXPECT_EQ(found[0]->where.line, 9);
    EXPECT_EQ(found[0]->where.path, "/output");
  }
}

TEST(OutputVersion, FixedOutputSizeThatDiffersIsAWarningNamingTheSizeUsed) {
  GraphDesc d;
  d.resources = {importedTex("img", false)};
  d.resources[0].texture.size = SizeSpec::absolute(256, 144);
  d.resources[0].where = at(3, 12, "/resources/img");
  d.passes = {pass("draw", {wr("color", "img")})};
  d.output = "img";
  Plan plan = compile(d, CompileOptions{Extent{640, 360}});
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  auto found = withCode(plan, DiagCode::output_size);
  ASSERT_EQ(found.size(), 1u) << dumpDiagnostics(plan);
  EXPECT_EQ(found[0]->severity, Severity::warning);
  EXPECT_EQ(found[0]->message,
            "output 'img' is 256x144 (its fixed size), not the requested output size 640x360: the image is 256x144 "
            "(resources sized \"output\" are 640x360)");
  EXPECT_EQ(found[0]->where.path, "/resources/img");
  // The same size: nothing to say.
  EXPECT_TRUE(compile(d, CompileOptions{Extent{256, 144}}).diagnostics.empty());
}

TEST(OutputVersion, TexturesLargerThanTheLimitAreRefusedWithTheirLocation) {
  GraphDesc d;
  d.resources = {tex("huge", Format::rgba8, SizeSpec::absolute(65536, 65536)), importedTex("out", false)};
  d.resources[0].where = at(4, 14, "/resources/huge");
  d.passes = {pass("fill", {wr("color", "huge")}), pass("present", {rd("src", "huge"), wr("color", "out")})};
  d.output = "out";
  Plan plan = compile(d);
  auto found = withCode(plan, DiagCode::invalid_resource);
  ASSERT_EQ(found.size(), 1u) << dumpDiagnostics(plan);
  EXPECT_EQ(found[0]->message,
            "texture 'huge' is 65536x65536, larger than 16384 pixels per side, the GL_MAX_TEXTURE_SIZE every "
            "OpenGL 4.5 device reaches");
  EXPECT_EQ(found[0]->where.path, "/resources/huge");
  // Another limit, and where it comes from.
  CompileOptions o;
  o.maxTextureSize = 8192;
  o.maxTextureSizeOrigin = "this device's GL_MAX_TEXTURE_SIZE";
  d.resources[0].texture.size = SizeSpec::absolute(8193, 16);
  const Plan limited = compile(d, o);
  found = withCode(limited, DiagCode::invalid_resource);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(contains(found[0]->message, "is 8193x16, larger than 8192 pixels per side, this device's"))
      << found[0]->message;
  // Relative sizes resolve against the output first.
  d.resources[0].texture.size = SizeSpec::relative(16.0f);
  const Plan scaled = compile(d);
  found = withCode(scaled, DiagCode::invalid_resource);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(contains(found[0]->message, "is 20480x11520 (at output size 1280x720), larger than 16384"))
      << found[0]->message;
  // A larger limit, or none, accepts it.
  o.maxTextureSize = 32768;
  EXPECT_TRUE(compile(d, o).ok());
  o.maxTextureSize = 0;
  EXPECT_TRUE(compile(d, o).ok());
}

// Messages about a slot name the version it binds, not only its resource.
TEST(OutputVersion, BindingMessagesNameTheBoundVersion) {
  GraphDesc d;
  d.resources = {tex("x"), tex("ms", Format::rgba8, SizeSpec::output(), 1, 4), importedTex("out", false)};
  d.passes = {
      pass("base", {wr("color", "x"), wr("ms", "ms")}),
      pass("lift", {rmw("color", "x", "x_1"), rmw("ms", "ms", "ms_1")}),
      pass("loop", {rd("src", "x_1"), rmw("color", "x_1", "x_2")}),
      pass("present", {rd("src", "x_2"), rd("m", "ms_1"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  auto loop = withCode(plan, DiagCode::feedback_loop);
  ASSERT_EQ(loop.size(), 1u) << dumpDiagnostics(plan);
  EXPECT_TRUE(contains(loop[0]->message,
                       "input 'src' reads 'x_1' (a version of 'x') while output 'color' binds 'x_2' (a version of "
                       "'x') as an attachment of the same pass"))
      << loop[0]->message;
  EXPECT_EQ(loop[0]->resource, "x_1");
  auto ms = withCode(plan, DiagCode::multisample_sampled);
  ASSERT_EQ(ms.size(), 1u) << dumpDiagnostics(plan);
  EXPECT_TRUE(contains(ms[0]->message, "input 'm' samples 'ms_1' (a version of 'ms'), which has 4 samples"))
      << ms[0]->message;
}

}  // namespace
