// Case 6: resizing between frames, through a full deferred pipeline with a
// scene (pipelines/deferred-light-volumes.json: G-buffer, ambient pass, light
// volumes, depth blit, forward light boxes, tone mapping). Each of 100 resizes
// recompiles the plan for the new size and rebuilds every texture at it; a
// frame is rendered after each; the GL objects alive stay the same number
// (nothing leaks per resize), every 10th frame matches a fresh executor's at
// that size byte for byte, the first size renders the same picture again at
// the end, and once the executor is gone every object it made is gone.
#include <GL/glcorearb.h>

#include <iostream>

#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"
#include "stability_util.h"

using namespace rgraph;
using namespace rgraph::stab;

namespace {

std::vector<int64_t> liveByKind() {
  std::vector<int64_t> v;
  for (int k = 0; k < static_cast<int>(gl::ObjectKind::count_); ++k) v.push_back(gl::liveObjects(static_cast<gl::ObjectKind>(k)));
  return v;
}

std::string kindsText(const std::vector<int64_t>& v) {
  std::string s;
  for (size_t k = 0; k < v.size(); ++k)
    s += std::string(k ? ", " : "") + gl::objectKindName(static_cast<gl::ObjectKind>(k)) + " " + std::to_string(v[k]);
  return s;
}

Extent textureExtent(uint32_t tex) {
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
  return {static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
}

size_t litPixels(const std::vector<uint8_t>& rgba) {
  size_t n = 0;
  for (size_t i = 0; i < rgba.size(); i += 4) n += (rgba[i] | rgba[i + 1] | rgba[i + 2]) > 8;
  return n;
}

}  // namespace

TEST_F(Stability, ResizeHundredTimesDeferredPipeline) {
  const PipelineConfig cfg = repoPipeline("deferred-light-volumes.json");
  const Scene scene = smallStillLife();
  const std::vector<std::string> sized = {"gPosition", "gNormal", "gAlbedoSpec", "gDepth", "hdr", "forwardDepth", "output"};
  const Extent first{64, 48};

  const std::vector<int64_t> before = liveByKind();
  const int64_t totalBefore = gl::liveObjectsTotal();
  std::vector<uint8_t> firstImage;
  int64_t objectsAtFirst = 0;
  size_t owned = 0, compared = 0, objectChanges = 0;
  {
    ShaderLibrary shaders;  // its programs are counted too: made and freed inside this scope
    Executor exec(cfg, processRegistry(), shaders, &scene);
    exec.resize(first);
    exec.renderFrame();
    firstImage = exec.readOutputRGBA8();
    ASSERT_GT(litPixels(firstImage), firstImage.size() / 4 / 3) << "the scene should fill the picture";
    objectsAtFirst = gl::liveObjectsTotal();
    owned = exec.ownedObjects();

    for (int i = 0; i < 100; ++i) {
      const Extent size{16u + static_cast<uint32_t>((i * 37) % 113), 16u + static_cast<uint32_t>((i * 53) % 97)};
      exec.resize(size);
      // The plan was compiled for this size and the textures rebuilt at it.
      ASSERT_EQ(exec.plan().output, size) << "resize " << i;
      ASSERT_EQ(exec.outputExtent(), size) << "resize " << i;
      for (const auto& r : sized) {
        ASSERT_NE(exec.textureOf(r), 0u) << r;
        ASSERT_EQ(textureExtent(exec.textureOf(r)), size) << r << " after resize " << i;
      }
      exec.renderFrame();
      const std::vector<uint8_t> img = exec.readOutputRGBA8();
      ASSERT_EQ(img.size(), size_t(size.width) * size.height * 4);
      // (Wide sizes show more background: the vertical field of view is fixed.)
      EXPECT_GT(litPixels(img), img.size() / 4 / 10) << "resize " << i << ": mostly black at " << size.width << "x"
                                                     << size.height;
      // Same objects alive at every size: nothing leaks per resize.
      if (gl::liveObjectsTotal() != objectsAtFirst || exec.ownedObjects() != owned) ++objectChanges;
      EXPECT_EQ(gl::liveObjectsTotal(), objectsAtFirst) << "resize " << i << ": " << kindsText(liveByKind());
      if (i % 10 == 9) {
        // The same picture a fresh executor renders at this size.
        Executor fresh(cfg, processRegistry(), shaders, &scene);
        fresh.resize(size);
        fresh.renderFrame();
        const Diff d = compare8(fresh.readOutputRGBA8(), img, size);
        EXPECT_EQ(d.maxAbs, 0) << "resize " << i << " (" << size.width << "x" << size.height << "): " << d.describe();
        ++compared;
      }
    }
    exec.resize(first);
    exec.renderFrame();
    const Diff back = compare8(firstImage, exec.readOutputRGBA8(), first);
    EXPECT_EQ(back.maxAbs, 0) << "back at the first size: " << back.describe();
    EXPECT_EQ(gl::liveObjectsTotal(), objectsAtFirst);
    std::cout << "[ measure  ] 100 resizes of " << cfg.graph.passes.size() << "-pass deferred pipeline: "
              << owned << " objects owned by the executor, " << objectsAtFirst - totalBefore
              << " GL objects alive with it (programs, scene buffers included) at every size (" << objectChanges
              << " changes); " << compared << " frames matched a fresh executor's byte for byte; back at "
              << first.width << "x" << first.height << ": " << back.describe() << std::endl;
    RecordProperty("objects_alive_with_executor", static_cast<int>(objectsAtFirst - totalBefore));
    RecordProperty("object_count_changes", static_cast<int>(objectChanges));
  }
  const std::vector<int64_t> after = liveByKind();
  std::cout << "[ measure  ] GL objects before: " << kindsText(before) << "\n             after:  " << kindsText(after)
            << std::endl;
  EXPECT_EQ(after, before) << "leaked: before " << kindsText(before) << "; after " << kindsText(after);
  EXPECT_EQ(gl::liveObjectsTotal(), totalBefore);
}
