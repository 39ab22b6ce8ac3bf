// Every graph diagnostic code: triggered, with pass/slot/resource and the
// source location copied from the description.
#include <gtest/gtest.h>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

void expectWhere(const Diagnostic& d, const SourceLocation& l) {
  EXPECT_EQ(d.where.file, l.file);
  EXPECT_EQ(d.where.line, l.line);
  EXPECT_EQ(d.where.column, l.column);
  EXPECT_EQ(d.where.path, l.path);
}

// Returns the single diagnostic with this code (fails the test otherwise).
const Diagnostic& only(const Plan& plan, DiagCode c) {
  auto found = withCode(plan, c);
  EXPECT_EQ(found.size(), 1u) << diagCodeName(c) << "\n" << dumpDiagnostics(plan);
  static const Diagnostic none;
  return found.empty() ? none : *found.front();
}

GraphDesc simple() {
  GraphDesc d;
  d.resources = {tex("gAlbedo"), importedTex("out", false)};
  d.passes = {pass("gbuffer", {wr("color", "gAlbedo")}), pass("present", {rd("src", "gAlbedo"), wr("color", "out")})};
  d.output = "out";
  return d;
}

TEST(Diagnostics, ValidGraphHasNone) {
  Plan plan = compile(simple());
  EXPECT_TRUE(plan.ok());
  EXPECT_TRUE(plan.diagnostics.empty()) << dumpDiagnostics(plan);
}

TEST(Diagnostics, UnknownResourceOnReadSuggestsAName) {
  GraphDesc d = simple();
  d.passes[1].uses[0].input = "gAlbdo";
  d.passes[1].uses[0].inputWhere = at(12, 18, "/passes/1/inputs/src");
  Plan plan = compile(d);
  EXPECT_FALSE(plan.ok());
  const Diagnostic& dg = only(plan, DiagCode::unknown_resource);
  EXPECT_EQ(dg.severity, Severity::error);
  EXPECT_EQ(dg.pass, "present");
  EXPECT_EQ(dg.slot, "src");
  EXPECT_EQ(dg.resource, "gAlbdo");
  EXPECT_TRUE(contains(dg.message, "input 'src' reads 'gAlbdo', which is not a declared resource")) << dg.message;
  EXPECT_TRUE(contains(dg.message, "did you mean 'gAlbedo'?")) << dg.message;
  expectWhere(dg, at(12, 18, "/passes/1/inputs/src"));
  EXPECT_EQ(formatDiagnostic(dg).rfind("graph.json:12:18: error: /passes/1/inputs/src: ", 0), 0u)
      << formatDiagnostic(dg);
  // The plan is still filled in.
  EXPECT_EQ(plan.passes.size(), 2u);
  EXPECT_EQ(plan.bindings.size(), 2u);
  EXPECT_FALSE(plan.bindings[1][0].resource.valid());
}

TEST(Diagnostics, UnknownResourceOnWriteAndOnOutput) {
  GraphDesc d = simple();
  d.passes[0].uses[0].output = "gAlbedoo";
  d.passes[0].uses[0].outputWhere = at(5, 3);
  d.output = "outt";
  d.outputWhere = at(30, 13, "/output");
  Plan plan = compile(d);
  auto found = withCode(plan, DiagCode::unknown_resource);
  ASSERT_EQ(found.size(), 2u) << dumpDiagnostics(plan);
  EXPECT_EQ(found[0]->pass, "gbuffer");
  EXPECT_EQ(found[0]->slot, "color");
  EXPECT_EQ(found[0]->resource, "gAlbedoo");
  EXPECT_TRUE(contains(found[0]->message, "did you mean 'gAlbedo'?")) << found[0]->message;
  expectWhere(*found[0], at(5, 3));
  EXPECT_EQ(found[1]->resource, "outt");
  EXPECT_TRUE(found[1]->pass.empty());
  expectWhere(*found[1], at(30, 13, "/output"));
  // gAlbedo is now never written: reported too, in the same run.
  EXPECT_EQ(withCode(plan, DiagCode::read_never_written).size(), 1u);
}

TEST(Diagnostics, LocationFallsBackToThePass) {
  GraphDesc d = simple();
  d.passes[1].uses[0].input = "nope";
  d.passes[1].where = at(40, 5, "/passes/1");
  Plan plan = compile(d);
  expectWhere(only(plan, DiagCode::unknown_resource), at(40, 5, "/passes/1"));
}

TEST(Diagnostics, ReadNeverWritten) {
  GraphDesc d = simple();
  d.resources.push_back(tex("gNormal"));
  d.passes[1].uses.push_back(rd("normal", "gNormal"));
  d.passes[1].uses.back().inputWhere = at(14, 7);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::read_never_written);
  EXPECT_EQ(dg.pass, "present");
  EXPECT_EQ(dg.slot, "normal");
  EXPECT_EQ(dg.resource, "gNormal");
  EXPECT_TRUE(contains(dg.message, "no pass writes it")) << dg.message;
  expectWhere(dg, at(14, 7));
}

TEST(Diagnostics, ReadNeverWrittenNamesTheDisabledWriter) {
  GraphDesc d = simple();
  d.passes[0].enabled = false;
  d.passes[1].uses[0].inputWhere = at(9, 2);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::read_never_written);
  EXPECT_EQ(dg.pass, "present");
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_TRUE(contains(dg.message, "pass 'gbuffer', is disabled")) << dg.message;
  expectWhere(dg, at(9, 2));
  EXPECT_TRUE(plan.passes[0].culled);
  EXPECT_EQ(plan.passes[0].reason, "disabled");
}

TEST(Diagnostics, ImportedWithoutContentIsNotReadable) {
  GraphDesc d = simple();
  d.resources.push_back(importedTex("history", false));
  d.passes[1].uses.push_back(rd("history", "history"));
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::read_never_written);
  EXPECT_EQ(dg.resource, "history");
  EXPECT_TRUE(contains(dg.message, "without content")) << dg.message;
}

TEST(Diagnostics, DuplicateWriterOfOneVersion) {
  GraphDesc d = simple();
  d.passes.insert(d.passes.begin() + 1, pass("gbuffer2", {wr("color", "gAlbedo")}));
  d.passes[1].uses[0].outputWhere = at(20, 9);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::duplicate_writer);
  EXPECT_EQ(dg.pass, "gbuffer2");
  EXPECT_EQ(dg.slot, "color");
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_TRUE(contains(dg.message, "pass 'gbuffer' already writes")) << dg.message;
  expectWhere(dg, at(20, 9));
}

TEST(Diagnostics, DuplicateWriterTwoSuccessorsOfOneVersion) {
  GraphDesc d = simple();
  d.passes.insert(d.passes.begin() + 1, pass("decals", {rmw("color", "gAlbedo", "gAlbedo_decals")}));
  d.passes.insert(d.passes.begin() + 2, pass("dirt", {rmw("color", "gAlbedo", "gAlbedo_dirt")}));
  d.passes[2].uses[0].inputWhere = at(22, 11);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::duplicate_writer);
  EXPECT_EQ(dg.pass, "dirt");
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_TRUE(contains(dg.message, "pass 'decals' already derives 'gAlbedo_decals'")) << dg.message;
  expectWhere(dg, at(22, 11));
}

TEST(Diagnostics, DuplicateWriterOutputNamesAnExistingVersion) {
  GraphDesc d = simple();
  d.resources.push_back(tex("other"));
  d.passes.insert(d.passes.begin() + 1, pass("blend", {rmw("color", "gAlbedo", "other")}));
  d.passes[1].uses[0].outputWhere = at(25, 4);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::duplicate_writer);
  EXPECT_EQ(dg.pass, "blend");
  EXPECT_EQ(dg.resource, "other");
  EXPECT_TRUE(contains(dg.message, "already a declared resource")) << dg.message;
  expectWhere(dg, at(25, 4));
}

// Issue 16: a pass that draws over 'gAlbedo' and names its result 'gAlbedo'
// too. One error, at that output, saying what to do; the readers of
// 'gAlbedo' and the output are not reported again as "no pass writes it".
TEST(Diagnostics, InPlaceWriteUnderItsOwnNameIsOneErrorSuggestingANewName) {
  GraphDesc d;
  d.resources = {tex("gAlbedo"), importedTex("out", false)};
  d.passes = {pass("decals", {rmw("color", "gAlbedo", "gAlbedo")}),
              pass("present", {rd("src", "gAlbedo"), wr("color", "out")})};
  d.passes[0].uses[0].outputWhere = at(7, 40, "/passes/0/outputs/color");
  d.output = "out";
  Plan plan = compile(d);
  EXPECT_FALSE(plan.ok());
  ASSERT_EQ(plan.diagnostics.size(), 1u) << dumpDiagnostics(plan);
  const Diagnostic& dg = plan.diagnostics[0];
  EXPECT_EQ(dg.code, DiagCode::duplicate_writer);
  EXPECT_EQ(dg.pass, "decals");
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_EQ(dg.message,
            "output 'color' names 'gAlbedo' as the version it produces, but 'gAlbedo' is the version it loads: "
            "drawing over a version produces a new one; give the new version a new name (e.g. 'gAlbedo_2') and "
            "read that one after this pass");
  expectWhere(dg, at(7, 40, "/passes/0/outputs/color"));

  // The same as the output image: one error too (not "never written").
  d.passes.pop_back();
  d.output = "gAlbedo";
  d.resources[0] = importedTex("gAlbedo", false);
  d.resources.pop_back();
  Plan asOutput = compile(d);
  EXPECT_EQ(withCode(asOutput, DiagCode::duplicate_writer).size(), 1u) << dumpDiagnostics(asOutput);
  EXPECT_TRUE(withCode(asOutput, DiagCode::output_never_written).empty()) << dumpDiagnostics(asOutput);
  EXPECT_TRUE(withCode(asOutput, DiagCode::read_never_written).empty()) << dumpDiagnostics(asOutput);
}

// The suggested name is one the graph does not use yet.
TEST(Diagnostics, SuggestedNewVersionNameIsUnused) {
  GraphDesc d;
  d.resources = {tex("hdr"), tex("hdr_2"), importedTex("out", false)};
  d.passes = {pass("sky", {rmw("color", "hdr", "hdr")}), pass("present", {rd("src", "hdr"), wr("color", "out")})};
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::duplicate_writer);
  EXPECT_TRUE(contains(dg.message, "(e.g. 'hdr_3')")) << dg.message;
}

TEST(Diagnostics, CycleNamesThePassesInOrder) {
  GraphDesc d;
  d.resources = {tex("x"), tex("y"), importedTex("out", false)};
  d.passes = {
      pass("a", {rd("src", "y"), wr("color", "x")}),
      pass("b", {rd("src", "x"), wr("color", "y")}),
      pass("present", {rd("src", "x"), wr("color", "out")}),
  };
  d.passes[0].where = at(3, 5, "/passes/0");
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::cycle);
  EXPECT_EQ(dg.message.rfind("cycle: a -> b -> a", 0), 0u) << dg.message;
  EXPECT_EQ(dg.pass, "a");
  expectWhere(dg, at(3, 5, "/passes/0"));
  ASSERT_EQ(plan.passes.size(), 3u);
  for (const auto& p : plan.passes) EXPECT_FALSE(p.order.valid());
  EXPECT_TRUE(plan.order.empty());
  EXPECT_EQ(plan.bindings.size(), 3u);
}

TEST(Diagnostics, CycleThroughWriteAfterRead) {
  // "peek" reads hdr version 0 (so it must run before "blend" overwrites it)
  // and also reads blend's result: impossible.
  GraphDesc d;
  d.resources = {tex("hdr"), tex("mix"), importedTex("out", false)};
  d.passes = {
      pass("base", {wr("color", "hdr")}),
      pass("blend", {rmw("color", "hdr", "hdr2")}),
      pass("peek", {rd("old", "hdr"), rd("new", "hdr2"), wr("color", "mix")}),
      pass("present", {rd("src", "mix"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::cycle);
  EXPECT_EQ(dg.message.rfind("cycle: blend -> peek -> blend", 0), 0u) << dg.message;
}

TEST(Diagnostics, LongerCycleAndUnrelatedPassesStayFilledIn) {
  GraphDesc d;
  d.resources = {tex("x"), tex("y"), tex("z"), importedTex("out", false)};
  d.passes = {
      pass("present", {rd("src", "x"), wr("color", "out")}),
      pass("c", {rd("src", "y"), wr("color", "z")}),
      pass("a", {rd("src", "z"), wr("color", "x")}),
      pass("b", {rd("src", "x"), wr("color", "y")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::cycle);
  EXPECT_EQ(dg.message.rfind("cycle: c -> a -> b -> c", 0), 0u) << dg.message;
  EXPECT_EQ(plan.passes[0].name, "present");
  EXPECT_FALSE(plan.passes[0].order.valid());
}

TEST(Diagnostics, FeedbackLoop) {
  GraphDesc d;
  d.resources = {tex("hdr", Format::rgba16f), importedTex("out", false)};
  d.passes = {
      pass("base", {wr("color", "hdr")}),
      pass("blur", {rd("src", "hdr"), rmw("color", "hdr", "hdr_blur")}),
      pass("present", {rd("src", "hdr_blur"), wr("color", "out")}),
  };
  d.passes[1].uses[0].inputWhere = at(17, 21);
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::feedback_loop);
  EXPECT_EQ(dg.pass, "blur");
  EXPECT_EQ(dg.slot, "src");
  EXPECT_EQ(dg.resource, "hdr");
  EXPECT_TRUE(contains(dg.message, "feedback loop")) << dg.message;
  expectWhere(dg, at(17, 21));
}

TEST(Diagnostics, FeedbackLoopWithDepthReadAttachment) {
  GraphDesc d;
  d.resources = {tex("depth", Format::depth32f), tex("ao", Format::r8), importedTex("out", false)};
  d.passes = {
      pass("prepass", {wr("depth", "depth", Access::depth_attachment)}),
      pass("ssao", {rd("depth", "depth"), rd("test", "depth", Access::depth_attachment_read), wr("color", "ao")}),
      pass("present", {rd("src", "ao"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  EXPECT_EQ(only(plan, DiagCode::feedback_loop).resource, "depth");
}

TEST(Diagnostics, AttachmentSizeAndSamplesMismatch) {
  GraphDesc d;
  d.resources = {tex("gColor"), tex("gNormal", Format::rgba16f, SizeSpec::relative(0.5f)),
                 tex("gDepth", Format::depth24, SizeSpec::output(), 1, 4), importedTex("out", false)};
  d.passes = {
      pass("gbuffer", {wr("color", "gColor"), wr("normal", "gNormal"), wr("depth", "gDepth", Access::depth_attachment)}),
      pass("present", {rd("a", "gColor"), rd("b", "gNormal"), wr("color", "out")}),
  };
  d.passes[0].uses[1].outputWhere = at(8, 15);
  d.passes[0].uses[2].outputWhere = at(9, 15);
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& size = only(plan, DiagCode::attachment_size_mismatch);
  EXPECT_EQ(size.pass, "gbuffer");
  EXPECT_EQ(size.slot, "normal");
  EXPECT_EQ(size.resource, "gNormal");
  EXPECT_TRUE(contains(size.message, "640x360")) << size.message;
  EXPECT_TRUE(contains(size.message, "1280x720")) << size.message;
  expectWhere(size, at(8, 15));
  const Diagnostic& samples = only(plan, DiagCode::attachment_samples_mismatch);
  EXPECT_EQ(samples.slot, "depth");
  EXPECT_EQ(samples.resource, "gDepth");
  expectWhere(samples, at(9, 15));
}

TEST(Diagnostics, DepthBlitFormatMismatch) {
  GraphDesc d;
  d.resources = {tex("d24", Format::depth24), tex("d32", Format::depth32f), tex("c"), importedTex("out", false)};
  d.passes = {
      pass("z", {wr("depth", "d24", Access::depth_attachment)}),
      pass("copy", {rd("src", "d24", Access::blit_src), wr("dst", "d32", Access::blit_dst)}),
      pass("shade", {rd("d", "d32"), wr("color", "out")}),
  };
  d.passes[1].uses[1].outputWhere = at(11, 2);
  d.output = "out";
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::depth_blit_format_mismatch);
  EXPECT_EQ(dg.pass, "copy");
  EXPECT_EQ(dg.resource, "d32");
  EXPECT_TRUE(contains(dg.message, "depth24")) << dg.message;
  EXPECT_TRUE(contains(dg.message, "depth32f")) << dg.message;
  expectWhere(dg, at(11, 2));
  // Colour blits between different formats are fine.
  d.resources[1].texture.format = Format::depth24;
  EXPECT_TRUE(compile(d).ok());
}

TEST(Diagnostics, RgbFloatAttachmentRefused) {
  GraphDesc d = simple();
  d.resources[0].texture.format = Format::rgb16f;
  d.passes[0].uses[0].outputWhere = at(4, 4);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::rgb_float_attachment);
  EXPECT_EQ(dg.pass, "gbuffer");
  EXPECT_EQ(dg.slot, "color");
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_TRUE(contains(dg.message, "rgba16f")) << dg.message;
  expectWhere(dg, at(4, 4));
  d.resources[0].texture.format = Format::rgb32f;
  EXPECT_TRUE(contains(only(compile(d), DiagCode::rgb_float_attachment).message, "rgba32f"));
  // As a storage image it is accepted.
  d.passes[0].uses[0].access = Access::storage_write;
  EXPECT_TRUE(compile(d).ok());
}

TEST(Diagnostics, MultisampleSampled) {
  GraphDesc d = simple();
  d.resources[0].texture.samples = 4;
  d.passes[1].uses[0].inputWhere = at(6, 6);
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::multisample_sampled);
  EXPECT_EQ(dg.pass, "present");
  EXPECT_EQ(dg.slot, "src");
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_TRUE(contains(dg.message, "4 samples")) << dg.message;
  expectWhere(dg, at(6, 6));
  d.passes[1].uses[0].acceptsMultisample = true;
  EXPECT_TRUE(compile(d).ok()) << dumpDiagnostics(compile(d));
}

TEST(Diagnostics, NoOutput) {
  GraphDesc d = simple();
  d.output.clear();
  d.outputWhere = at(1, 1, "");
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::no_output);
  expectWhere(dg, at(1, 1, ""));
  EXPECT_FALSE(plan.outputResource.valid());
  // Nothing reaches an output, so everything without a side effect is culled.
  EXPECT_TRUE(plan.order.empty());
}

TEST(Diagnostics, EmptyDescriptionOnlyLacksAnOutput) {
  Plan plan = compile(GraphDesc{});
  ASSERT_EQ(plan.diagnostics.size(), 1u);
  EXPECT_EQ(plan.diagnostics[0].code, DiagCode::no_output);
}

TEST(Diagnostics, OutputNeverWritten) {
  GraphDesc d = simple();
  d.passes.pop_back();
  d.outputWhere = at(50, 12, "/output");
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::output_never_written);
  EXPECT_EQ(dg.resource, "out");
  expectWhere(dg, at(50, 12, "/output"));
  // Written only by a disabled pass.
  GraphDesc e = simple();
  e.passes[1].enabled = false;
  Plan p2 = compile(e);
  const Diagnostic& dg2 = only(p2, DiagCode::output_never_written);
  EXPECT_EQ(dg2.pass, "present");
  EXPECT_TRUE(contains(dg2.message, "disabled")) << dg2.message;
}

TEST(Diagnostics, DuplicateResource) {
  GraphDesc d = simple();
  d.resources[0].where = at(2, 3, "/resources/gAlbedo");
  d.resources.push_back(tex("gAlbedo", Format::rgba16f));
  d.resources.back().where = at(7, 3, "/resources/2");
  Plan plan = compile(d);
  const Diagnostic& dg = only(plan, DiagCode::duplicate_resource);
  EXPECT_EQ(dg.resource, "gAlbedo");
  EXPECT_TRUE(contains(dg.message, "graph.json:2")) << dg.message;
  expectWhere(dg, at(7, 3, "/resources/2"));
  EXPECT_EQ(plan.resources.size(), 3u);
  EXPECT_FALSE(plan.resources[2].physical.valid());
}

TEST(Diagnostics, InvalidResources) {
  GraphDesc d = simple();
  d.resources.push_back(tex("zero", Format::rgba8, SizeSpec::absolute(0, 16)));
  d.resources.push_back(tex("negscale", Format::rgba8, SizeSpec::relative(-1.0f)));
  d.resources.push_back(tex("samples3", Format::rgba8, SizeSpec::output(), 1, 3));
  d.resources.push_back(tex("mips", Format::rgba8, SizeSpec::absolute(16, 16), 6));  // 16x16 has 5 levels
  d.resources.push_back(buffer("empty", 0));
  d.resources.push_back(tex("msaamips", Format::rgba8, SizeSpec::output(), 0, 4));
  for (size_t i = 2; i < d.resources.size(); ++i) d.resources[i].where = at(static_cast<int>(100 + i));
  Plan plan = compile(d);
  auto found = withCode(plan, DiagCode::invalid_resource);
  ASSERT_EQ(found.size(), 6u) << dumpDiagnostics(plan);
  const char* names[] = {"zero", "negscale", "samples3", "mips", "empty", "msaamips"};
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(found[i]->resource, names[i]);
    EXPECT_EQ(found[i]->where.line, static_cast<int>(102 + i));
  }
  EXPECT_TRUE(contains(found[3]->message, "at most 5")) << found[3]->message;
  // Mip counts within the chain are fine.
  GraphDesc ok = simple();
  ok.resources.push_back(tex("m5", Format::rgba8, SizeSpec::absolute(16, 16), 5));
  EXPECT_TRUE(compile(ok).ok());
}

TEST(Diagnostics, AccessFormatMismatch) {
  GraphDesc d;
  d.resources = {tex("depth", Format::depth24), tex("color"), tex("c2"), buffer("buf", 64),
                 importedTex("out", false)};
  d.passes = {
      pass("wrong", {wr("color", "depth"), wr("depth", "color", Access::depth_attachment)}),
      pass("bufsample", {rd("b", "buf"), wr("color", "c2")}),
      pass("present", {rd("a", "depth"), rd("b", "color"), rd("c", "c2"), wr("color", "out")}),
  };
  d.passes[0].uses[0].outputWhere = at(60, 1);
  d.passes[0].uses[1].outputWhere = at(61, 1);
  d.output = "out";
  Plan plan = compile(d);
  auto found = withCode(plan, DiagCode::access_format_mismatch);
  ASSERT_GE(found.size(), 2u) << dumpDiagnostics(plan);
  EXPECT_EQ(found[0]->pass, "wrong");
  EXPECT_EQ(found[0]->slot, "color");
  EXPECT_EQ(found[0]->resource, "depth");
  EXPECT_TRUE(contains(found[0]->message, "depth format")) << found[0]->message;
  expectWhere(*found[0], at(60, 1));
  EXPECT_EQ(found[1]->slot, "depth");
  EXPECT_EQ(found[1]->resource, "color");
  EXPECT_TRUE(contains(found[1]->message, "colour format")) << found[1]->message;
  // The depth formats it suggests: depthFormats(), every one.
  EXPECT_TRUE(contains(found[1]->message, "(use depth24, depth32f, depth24_stencil8 or depth32f_stencil8)"))
      << found[1]->message;
  expectWhere(*found[1], at(61, 1));
  // A buffer bound as a sampled texture.
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[2]->pass, "bufsample");
  EXPECT_EQ(found[2]->resource, "buf");
}

TEST(Diagnostics, ManyErrorsReportedInOneRun) {
  GraphDesc d = simple();
  d.resources.push_back(tex("gAlbedo"));                     // duplicate_resource
  d.resources.push_back(tex("rgb", Format::rgb32f));
  d.passes.push_back(pass("bad", {rd("x", "missing"), wr("color", "rgb")}, true));  // unknown + rgb float
  d.passes.push_back(pass("bad2", {rd("x", "rgb"), wr("color", "gAlbedo")}));        // duplicate writer
  Plan plan = compile(d);
  EXPECT_EQ(withCode(plan, DiagCode::duplicate_resource).size(), 1u);
  EXPECT_EQ(withCode(plan, DiagCode::unknown_resource).size(), 1u);
  EXPECT_EQ(withCode(plan, DiagCode::rgb_float_attachment).size(), 1u);
  EXPECT_EQ(withCode(plan, DiagCode::duplicate_writer).size(), 1u);
  EXPECT_EQ(plan.passes.size(), 4u);
  EXPECT_EQ(plan.bindings.size(), 4u);
}

TEST(Diagnostics, GarbageNeverCrashes) {
  GraphDesc d;
  d.resources = {tex(""), tex("a"), tex("a")};
  d.passes = {pass("", {ResourceUse{}, wr("", ""), rmw("", "", "")}),
              pass("loop1", {rmw("c", "v2", "v1")}), pass("loop2", {rmw("c", "v1", "v2")}),
              pass("self", {rmw("c", "v3", "v3")}), pass("p", {rd("s", "v1"), wr("o", "a")})};
  d.output = "v1";
  Plan plan = compile(d);
  EXPECT_FALSE(plan.ok());
  EXPECT_EQ(plan.passes.size(), 5u);
  EXPECT_GE(withCode(plan, DiagCode::read_never_written).size(), 2u) << dumpDiagnostics(plan);
  EXPECT_FALSE(toDot(d, plan).empty());
}

}  // namespace
