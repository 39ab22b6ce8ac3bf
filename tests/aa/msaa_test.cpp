// pipelines/forward-msaa.json, the anti-aliasing baseline: forward.json drawn
// into 4x multisampled targets and resolved by a blit. Inside surfaces it
// must be forward.json (shading runs once per pixel either way); on geometry
// edges it must differ, towards the supersampled reference.
#include <cstdio>

#include "aa/aa_util.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::aatest;

namespace {

constexpr Extent kSize{192, 192};

class ForwardMsaa : public rtest::RenderTest {};

}  // namespace

TEST_F(ForwardMsaa, MatchesForwardInsideSurfacesAndAntialiasesEdges) {
  const Scene scene = makeLearnOpenGLScene();
  const PipelineConfig forward = shippedPipeline("forward.json");
  const PipelineConfig msaa = shippedPipeline("forward-msaa.json");
  ASSERT_EQ(msaa.graph.resources[0].name, "hdr");
  ASSERT_EQ(msaa.graph.resources[0].texture.samples, 4u) << "the baseline must draw multisampled";
  const Image plain = rtest::render(forward, scene, kSize, *shaders);
  const Image aa = rtest::render(msaa, scene, kSize, *shaders);
  const Image ref = supersampled(forward, scene, kSize, 4, *shaders);
  EXPECT_GT(rtest::coverage(aa, {0, 0, 0}), 0.2) << rtest::saveImage(aa, "forward-msaa");

  // Away from edges (2 pixels from any strong gradient of the plain frame or
  // the reference): the same pixels within 1/255 (half-float resolve).
  const Mask edges = edgeMask(plain, 16);
  const Mask refEdges = edgeMask(ref, 16);
  Mask anyEdge(edges.size());
  for (size_t i = 0; i < edges.size(); ++i) anyEdge[i] = edges[i] || refEdges[i];
  const Mask interior = awayFrom(anyEdge, kSize, 2);
  const Error inside = measure(aa, plain, &interior);
  std::printf("[ measure  ] msaa vs forward away from edges: %s\n", inside.describe().c_str());
  ASSERT_GT(inside.pixels, kSize.width * kSize.height / 4);
  EXPECT_LE(inside.maxAbs, 1) << rtest::saveImage(aa, "forward-msaa") << " " << rtest::saveImage(plain, "forward");

  // On the reference's edges: MSAA differs from the plain frame, and is
  // closer to the 16-sample reference by a clear margin.
  const Error plainEdges = measure(plain, ref, &refEdges);
  const Error aaEdges = measure(aa, ref, &refEdges);
  const Error changed = measure(aa, plain, &refEdges);
  std::printf("[ measure  ] edges (%zu px): plain %s; msaa %s; msaa vs plain %s\n",
              refEdges.size() ? count(refEdges) : 0, plainEdges.describe().c_str(), aaEdges.describe().c_str(),
              changed.describe().c_str());
  ASSERT_GT(count(refEdges), 500u);
  EXPECT_GE(changed.maxAbs, 64) << "the edges are not antialiased";
  EXPECT_GE(aaEdges.psnr - plainEdges.psnr, 4.0) << "MSAA edges are not closer to the supersampled reference";
}
