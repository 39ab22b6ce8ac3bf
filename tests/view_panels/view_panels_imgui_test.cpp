// The panels drawn into a Dear ImGui frame with no window and no back end
// (the font atlas built on the CPU): every panel draws on the headless
// context, the inspector shows its display texture, and a parameter edit
// made through the widgets comes back as new pipeline text.
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>  // ImGui::ActivateItem: a click without a mouse

#include <glm/gtc/type_ptr.hpp>

#include "rgraph/renderer.h"
#include "test_support.h"
#include "view_panels.h"
#include "view_test_util.h"

namespace {
using namespace rgraph;

const std::string& kDefault = viewtest::kDefaultPipeline;

class ViewPanelsImgui : public ::testing::Test {
 protected:
  void SetUp() override {
    testsupport::sharedGlContext();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(1024, 2048);
    io.IniFilename = nullptr;
    unsigned char* pixels;
    int w, h;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  void TearDown() override { ImGui::DestroyContext(); }

  // One ImGui frame with `body` in a window; the draw data it produced.
  template <class F>
  ImDrawData* frame(F&& body) {
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(1000, 2000));
    ImGui::Begin("panel");
    body();
    ImGui::End();
    ImGui::Render();
    return ImGui::GetDrawData();
  }
};

bool drawsTexture(const ImDrawData* data, uint32_t texture) {
  for (int l = 0; l < data->CmdListsCount; ++l)
    for (const ImDrawCmd& cmd : data->CmdLists[l]->CmdBuffer)
      if (cmd.TextureId == reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture))) return true;
  return false;
}

TEST_F(ViewPanelsImgui, PlanParametersAndInspectorDrawOnTheHeadlessContext) {
  auto r = viewtest::defaultRenderer({64, 48});
  ASSERT_TRUE(r);
  view::ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("gNormal");
  view::ParamEditor editor(kDefault);
  r->render();

  std::optional<std::string> edit;
  ImDrawData* data = frame([&] {
    view::drawPlanPanel(*r);
    edit = editor.draw(*r);
    inspector.draw(*r);
  });
  ASSERT_NE(data, nullptr);
  EXPECT_GT(data->TotalVtxCount, 1000);
  EXPECT_FALSE(edit) << "no input, no edit";
  const uint32_t shown = inspector.renderDisplay();
  ASSERT_NE(shown, 0u);
  EXPECT_TRUE(drawsTexture(data, shown)) << "the inspector shows its display texture";
}

// ImGui's remote activation (what a click does) on the "markers" checkbox of
// default.json's light_boxes pass: the editor gives the file's text with only
// that value flipped, which the renderer takes.
TEST_F(ViewPanelsImgui, ClickingACheckboxGivesTheEditedPipeline) {
  auto r = viewtest::defaultRenderer({48, 32});
  ASSERT_TRUE(r);
  view::ParamEditor editor(kDefault);
  auto doc = nlohmann::ordered_json::parse(editor.text());
  ASSERT_EQ(doc["passes"][4]["name"], "light_boxes");
  ASSERT_EQ(doc["passes"][4]["params"]["markers"], true);
  std::optional<std::string> edit;
  for (int i = 0; i < 3 && !edit; ++i)
    frame([&] {
      ImGui::PushID(4);  // the editor's ID path: pass index, its tree node, the parameter
      ImGui::PushID("pass");
      const ImGuiID markers = ImGui::GetID("markers");
      ImGui::PopID();
      ImGui::PopID();
      if (i == 0) ImGui::ActivateItem(markers);
      edit = editor.draw(*r);
    });
  ASSERT_TRUE(edit) << "the click gave no edit";
  doc["passes"][4]["params"]["markers"] = false;
  EXPECT_EQ(*edit, doc.dump(2) + "\n");
  Diagnostics diags;
  EXPECT_TRUE(r->reloadJson(*edit, diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
}

// What a panel writes as text (ImGui's log, taken through the clipboard hook).
std::string loggedText;
void captureClipboard(void*, const char* text) { loggedText = text; }

TEST_F(ViewPanelsImgui, ThePlanPanelShowsCulledPassesAliasingMemoryAndWhatTheTimesAre) {
  RendererOptions options;
  options.size = {48, 32};
  Diagnostics diags;
  auto r = Renderer::fromJson(viewtest::kAliasing, "aliasing.json", options, diags);
  ASSERT_TRUE(r);
  r->render();
  ImGui::GetIO().SetClipboardTextFn = captureClipboard;
  frame([&] {
    ImGui::LogToClipboard();
    view::drawPlanPanel(*r);
    ImGui::LogFinish();
  });
  const Plan& plan = r->plan();
  const std::string& text = loggedText;
  EXPECT_NE(text.find("5 passes run, 1 culled"), std::string::npos) << text;
  EXPECT_NE(text.find("culled: " + plan.passes[5].reason), std::string::npos) << text;
  EXPECT_NE(text.find(r->cpuTimed() ? "CPU time, glFinish after each pass" : "GPU timer queries"), std::string::npos)
      << text;
  // a and c share physical texture #N: both rows say so.
  const std::string shared = "phys #" + std::to_string(plan.resources[0].physical.value()) + " (shared)";
  const size_t first = text.find(shared);
  ASSERT_NE(first, std::string::npos) << text;
  EXPECT_NE(text.find(shared, first + 1), std::string::npos) << text;
  char memory[160];
  std::snprintf(memory, sizeof(memory), "%.2f MiB allocated, %.2f MiB without aliasing",
                double(plan.allocatedBytes) / (1024.0 * 1024.0), double(plan.naiveBytes) / (1024.0 * 1024.0));
  EXPECT_NE(text.find(memory), std::string::npos) << text;
  EXPECT_LT(plan.allocatedBytes, plan.naiveBytes);
  for (const Renderer::PassTiming& t : r->timings()) EXPECT_NE(text.find(t.name), std::string::npos) << t.name;
}

// With GPU timer queries (forced: llvmpipe times on the CPU clock) the times
// are of an earlier frame, and the panel says which.
TEST_F(ViewPanelsImgui, ThePlanPanelSaysWhichFrameGpuTimesAreOf) {
  RendererOptions options;
  options.size = {48, 32};
  options.gpuTimerQueries = true;
  Diagnostics diags;
  auto r = Renderer::fromJson(viewtest::kAliasing, "aliasing.json", options, diags);
  ASSERT_TRUE(r);
  ImGui::GetIO().SetClipboardTextFn = captureClipboard;
  auto panelText = [&] {
    frame([&] {
      ImGui::LogToClipboard();
      view::drawPlanPanel(*r);
      ImGui::LogFinish();
    });
    return loggedText;
  };
  r->render();
  ASSERT_FALSE(r->cpuTimed());
  EXPECT_NE(panelText().find("no frame's times in yet"), std::string::npos) << loggedText;
  r->collectTimings(/*wait=*/true);
  r->render();
  ASSERT_TRUE(r->timingsFrame());
  const std::string expected = "of frame " + std::to_string(*r->timingsFrame()) + " (" +
                               std::to_string(r->frameIndex() - 1 - *r->timingsFrame()) + " behind)";
  EXPECT_NE(panelText().find(expected), std::string::npos) << loggedText;
}

// The value under the cursor: the panel prints the texel it reads at the
// mouse; it is the copy's texel at those coordinates (rows from the top).
TEST_F(ViewPanelsImgui, TheInspectorPrintsTheValueUnderTheCursor) {
  auto r = viewtest::defaultRenderer({64, 48});
  ASSERT_TRUE(r);
  view::ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("gPosition");
  r->render();
  ImGui::GetIO().SetClipboardTextFn = captureClipboard;
  std::vector<std::pair<unsigned, unsigned>> seen;
  for (const ImVec2 mouse : {ImVec2(300, 400), ImVec2(700, 250)}) {
    ImGui::GetIO().MousePos = mouse;
    frame([&] {
      ImGui::LogToClipboard();
      inspector.draw(*r);
      ImGui::LogFinish();
    });
    const size_t at = loggedText.find("): ");
    ASSERT_NE(at, std::string::npos) << "no value under the cursor at " << mouse.x << "," << mouse.y << ":\n"
                                     << loggedText;
    unsigned x = 0, y = 0;
    ASSERT_EQ(std::sscanf(loggedText.c_str() + loggedText.rfind('(', at), "(%u, %u)", &x, &y), 2) << loggedText;
    seen.emplace_back(x, y);
    const glm::vec4 v = inspector.readCapturedTexel(x, y);
    const std::vector<float> all = inspector.readCaptured();
    EXPECT_EQ(v, glm::make_vec4(&all[(size_t(y) * 64 + x) * 4])) << "readCapturedTexel is rows from the top";
    char want[128];
    std::snprintf(want, sizeof(want), "(%u, %u): %.5g %.5g %.5g %.5g", x, y, v.r, v.g, v.b, v.a);
    EXPECT_NE(loggedText.find(want), std::string::npos) << want << "\n" << loggedText;
  }
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_GT(seen[1].first, seen[0].first) << "the mouse moved right";
  EXPECT_LT(seen[1].second, seen[0].second) << "the mouse moved up";
}

// At 960x540, the smallest window the viewer is laid out for, drawPanels keeps its windows inside the
// display and the inspector's whole image on screen (it once sat below the visible part of one long window).
TEST_F(ViewPanelsImgui, At960x540ThePanelsAndTheInspectorImageAreOnScreen) {
  const ImVec2 display(960, 540);
  ImGui::GetIO().DisplaySize = display;
  auto r = viewtest::defaultRenderer({96, 54});
  ASSERT_TRUE(r);
  view::ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("gNormal");
  view::ParamEditor editor(kDefault);
  r->render();
  ImDrawData* data = nullptr;
  for (int i = 0; i < 2; ++i) {  // the second frame: sizes settled
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    ImGui::NewFrame();
    view::drawPanels(*r, editor, inspector);
    ImGui::Render();
    data = ImGui::GetDrawData();
  }
  for (const char* name : {"rgraph", "Inspector"}) {
    const ImGuiWindow* w = ImGui::FindWindowByName(name);
    ASSERT_NE(w, nullptr) << name;
    EXPECT_GE(w->Pos.x, 0.0f) << name;
    EXPECT_GE(w->Pos.y, 0.0f) << name;
    EXPECT_LE(w->Pos.x + w->Size.x, display.x) << name;
    EXPECT_LE(w->Pos.y + w->Size.y, display.y) << name;
  }
  const ImTextureID image = reinterpret_cast<ImTextureID>(static_cast<intptr_t>(inspector.renderDisplay()));
  size_t corners = 0;
  for (int l = 0; l < data->CmdListsCount; ++l) {
    const ImDrawList* list = data->CmdLists[l];
    for (const ImDrawCmd& cmd : list->CmdBuffer) {
      if (cmd.TextureId != image) continue;
      for (unsigned i = 0; i < cmd.ElemCount; ++i) {
        const ImVec2 p = list->VtxBuffer[list->IdxBuffer[cmd.IdxOffset + i] + cmd.VtxOffset].pos;
        ++corners;
        EXPECT_TRUE(p.x >= 0 && p.y >= 0 && p.x <= display.x && p.y <= display.y) << p.x << "," << p.y;
        EXPECT_TRUE(p.x >= cmd.ClipRect.x && p.y >= cmd.ClipRect.y && p.x <= cmd.ClipRect.z && p.y <= cmd.ClipRect.w)
            << "clipped by its window at " << p.x << "," << p.y;
      }
    }
  }
  EXPECT_EQ(corners, 6u) << "the image drawn once (two triangles)";
}

// The Shadows tab (brought to the front as the script's `panel shadows` does) shows the budget lines.
TEST_F(ViewPanelsImgui, TheShadowsTabShowsTheBudget) {
  auto r = viewtest::shadowRenderer(viewtest::smallMapsPipeline());
  ASSERT_TRUE(r);
  view::ResourceInspector inspector;
  view::ParamEditor editor(viewtest::kShadowPipeline);
  r->render();
  ImGui::GetIO().SetClipboardTextFn = captureClipboard;
  std::string tab = "shadows";
  for (int i = 0; i < 2; ++i) {  // a tab asked for is shown from the next frame
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    ImGui::NewFrame();
    ImGui::LogToClipboard();
    view::drawPanels(*r, editor, inspector, &tab);
    ImGui::LogFinish();
    ImGui::Render();
  }
  EXPECT_TRUE(tab.empty()) << "the request is taken";
  const std::vector<std::string> lines = view::shadowPanelLines(*r);
  ASSERT_GT(lines.size(), 8u);
  for (const std::string& l : lines)
    EXPECT_NE(loggedText.find(l.substr(l.find_first_not_of(' '))), std::string::npos) << l << "\n" << loggedText;
}

// After an accepted edit the pipeline running is not the file's: the panel says so until the file is read again.
TEST_F(ViewPanelsImgui, TheParametersPanelSaysWhenThePipelineIsEditedInMemory) {
  auto r = viewtest::defaultRenderer({48, 32});
  ASSERT_TRUE(r);
  view::ParamEditor editor(kDefault);
  ImGui::GetIO().SetClipboardTextFn = captureClipboard;
  auto panelText = [&] {
    frame([&] {
      ImGui::LogToClipboard();
      editor.draw(*r);
      ImGui::LogFinish();
    });
    return loggedText;
  };
  EXPECT_EQ(panelText().find("edited in memory"), std::string::npos) << loggedText;
  std::string error;
  const auto text = editor.withParam("tonemap", "gamma", "2.2", error);
  ASSERT_TRUE(text) << error;
  editor.accept(*text);
  EXPECT_NE(panelText().find("edited in memory: differs from " + kDefault + " until saved"), std::string::npos)
      << loggedText;
  ASSERT_TRUE(editor.reread());
  EXPECT_EQ(panelText().find("edited in memory"), std::string::npos) << loggedText;
}

}  // namespace
