// rgraph view's script parser and camera controls, without a window.
#include "view_script.h"

#include <gtest/gtest.h>

#include <cmath>

#include "view_camera.h"

namespace rgraph::view {
namespace {

using K = ScriptCommand::Kind;

TEST(ViewScript, ParsesEveryCommandWithItsLine) {
  std::string error;
  const auto cmds = parseScript(
      "# comment\ncamera 1 2 3 0 0 0 60\nwait 5\nscreenshot a.png\nui on\nparam tonemap gamma 2.2\n"
      "resize 200 150\nwaitfile done\n\nquit\n",
      "s.txt", error);
  ASSERT_EQ(error, "");
  ASSERT_EQ(cmds.size(), 8u);
  EXPECT_EQ(cmds[0].kind, K::Camera);
  EXPECT_EQ(cmds[0].line, 2);
  EXPECT_EQ(cmds[0].numbers, (std::vector<float>{1, 2, 3, 0, 0, 0, 60}));
  EXPECT_EQ(cmds[1].kind, K::Wait);
  EXPECT_EQ(cmds[2].words, std::vector<std::string>{"a.png"});
  EXPECT_EQ(cmds[3].words, std::vector<std::string>{"on"});
  EXPECT_EQ(cmds[4].words, (std::vector<std::string>{"tonemap", "gamma", "2.2"}));
  EXPECT_EQ(cmds[5].numbers, (std::vector<float>{200, 150}));
  EXPECT_EQ(cmds[6].kind, K::WaitFile);
  EXPECT_EQ(cmds[7].kind, K::Quit);
  EXPECT_EQ(cmds[7].line, 10);
}

// The animation clock: time SECONDS, play, pause.
TEST(ViewScript, TimePlayAndPause) {
  std::string error;
  const auto cmds = parseScript("time 1.25\nplay\npause\n", "s.txt", error);
  ASSERT_EQ(error, "");
  ASSERT_EQ(cmds.size(), 3u);
  EXPECT_EQ(cmds[0].kind, K::Time);
  EXPECT_EQ(cmds[0].numbers, std::vector<float>{1.25f});
  EXPECT_EQ(cmds[1].kind, K::Play);
  EXPECT_EQ(cmds[2].kind, K::Pause);
}

TEST(ViewScript, InspectTakesAResourceALayerAndAMip) {
  std::string error;
  const auto cmds =
      parseScript("inspect gDepth\ninspect shadowAtlas 5\ninspect bloom 0 3\npanel shadows\n", "s.txt", error);
  ASSERT_EQ(cmds.size(), 4u) << error;
  for (int i = 0; i < 3; ++i) EXPECT_EQ(cmds[size_t(i)].kind, K::Inspect);
  EXPECT_EQ(cmds[0].words, std::vector<std::string>{"gDepth"});
  EXPECT_EQ(cmds[0].numbers, (std::vector<float>{0, 0})) << "layer and mip 0 when left out";
  EXPECT_EQ(cmds[1].words, std::vector<std::string>{"shadowAtlas"});
  EXPECT_EQ(cmds[1].numbers, (std::vector<float>{5, 0}));
  EXPECT_EQ(cmds[2].numbers, (std::vector<float>{0, 3}));
  EXPECT_EQ(cmds[3].kind, K::Panel);
  EXPECT_EQ(cmds[3].words, std::vector<std::string>{"shadows"});
}

TEST(ViewScript, PickTakesAWindowPixel) {
  std::string error;
  const auto cmds = parseScript("pick 80 60\n", "s.txt", error);
  ASSERT_EQ(cmds.size(), 1u) << error;
  EXPECT_EQ(cmds[0].kind, K::Pick);
  EXPECT_EQ(cmds[0].numbers, (std::vector<float>{80, 60}));
}

TEST(ViewScript, JsonValuesMayContainSpaces) {
  std::string error;
  const auto cmds = parseScript("param ambient color [0.1, 0.2, 0.3]\n", "s.txt", error);
  ASSERT_EQ(cmds.size(), 1u) << error;
  EXPECT_EQ(cmds[0].words[2], "[0.1, 0.2, 0.3]");
}

TEST(ViewScript, ErrorsNameFileAndLine) {
  struct Case {
    const char* text;
    const char* error;
  };
  for (const Case& c : {
           Case{"wait 1\nzoom 3\n", "s.txt:2: error: unknown command 'zoom'"},
           Case{"camera 1 2 3 4 5\n", "s.txt:1: error: 'camera' expects PX PY PZ TX TY TZ [FOV], got 5"},
           Case{"camera 1 2 3 4 5 6 190\n", "s.txt:1: error: 'camera': the field of view must be between 0 and 180"},
           Case{"\n\nwait -1\n", "s.txt:3: error: 'wait' needs whole numbers from 0"},
           Case{"resize 10 nan\n", "s.txt:1: error: 'resize': 'nan' is not a number"},
           Case{"ui maybe\n", "s.txt:1: error: 'ui' expects on or off"},
           Case{"param a b\n", "s.txt:1: error: 'param' expects PASS NAME JSON-VALUE"},
           Case{"quit now\n", "s.txt:1: error: 'quit' takes no arguments"},
           Case{"inspect\n", "s.txt:1: error: 'inspect' expects RESOURCE [LAYER [MIP]]"},
           Case{"inspect atlas 1 2 3\n", "s.txt:1: error: 'inspect' expects RESOURCE [LAYER [MIP]]"},
           Case{"inspect atlas x\n", "s.txt:1: error: 'inspect': 'x' is not a number"},
           Case{"inspect atlas 1.5\n", "s.txt:1: error: 'inspect' needs whole numbers from 0 to 65535"},
           Case{"inspect atlas -1\n", "s.txt:1: error: 'inspect' needs whole numbers from 0 to 65535"},
           Case{"panel camera\n", "s.txt:1: error: 'panel' expects plan, parameters or shadows"},
           Case{"pick 1\n", "s.txt:1: error: 'pick' expects X Y, got 1 argument(s)"},
           Case{"pick 1 -2\n", "s.txt:1: error: 'pick' needs whole numbers from 0 to 65535"},
           Case{"pick 1 y\n", "s.txt:1: error: 'pick': 'y' is not a number (expected X Y)"},
           Case{"time -1\n", "s.txt:1: error: 'time' needs seconds >= 0"},
           Case{"time soon\n", "s.txt:1: error: 'time': 'soon' is not a number (expected SECONDS)"},
           Case{"play 2\n", "s.txt:1: error: 'play' takes no arguments"},
       }) {
    std::string error;
    EXPECT_TRUE(parseScript(c.text, "s.txt", error).empty()) << c.text;
    EXPECT_EQ(error.rfind(c.error, 0), 0u) << "script: " << c.text << "\nerror: " << error;
  }
}

TEST(ViewScript, MissingFileIsAnError) {
  std::string error;
  EXPECT_TRUE(loadScript("/nonexistent/script.txt", error).empty());
  EXPECT_EQ(error, "/nonexistent/script.txt: error: cannot read the script file (no such file)");
}

// A folder opens and reads as an empty script (which never quits): refused, as anything but a regular file.
TEST(ViewScript, AFolderOrADeviceIsNotAScript) {
  std::string error;
  EXPECT_TRUE(loadScript("/tmp", error).empty());
  EXPECT_EQ(error, "/tmp: error: cannot read the script file (it is a folder)");
  error.clear();
  EXPECT_TRUE(loadScript("/dev/null", error).empty());
  EXPECT_EQ(error, "/dev/null: error: cannot read the script file (not a regular file)");
}

Camera start() {
  Camera c;
  c.position = {0, 0, 5};
  c.target = {0, 0, 0};
  c.fovY = 50;
  return c;
}

TEST(ViewCamera, OrbitKeepsDistanceAndTarget) {
  CameraController cc;
  cc.setHome(start());
  cc.orbit(100, 40);
  EXPECT_NEAR(glm::length(cc.camera().position - cc.camera().target), 5.0f, 1e-4f);
  EXPECT_EQ(cc.camera().target, glm::vec3(0));
  EXPECT_GT(std::abs(cc.camera().position.x), 0.1f);  // it moved
  EXPECT_GT(cc.camera().position.y, 0.1f);
}

TEST(ViewCamera, OrbitStopsShortOfThePole) {
  CameraController cc;
  cc.setHome(start());
  cc.orbit(0, 100000);  // lookAt keeps an orientation, and the camera does not tip over the top
  EXPECT_LT(cc.camera().position.y, 5.0f);
  EXPECT_GT(cc.camera().position.y, 4.99f);
  EXPECT_GT(cc.camera().position.z, 1e-3f);
}

TEST(ViewCamera, ZoomApproachesButNeverPassesTheTarget) {
  CameraController cc;
  cc.setHome(start());
  cc.zoom(1);
  EXPECT_NEAR(cc.camera().position.z, 4.5f, 1e-4f);
  cc.zoom(1000);
  EXPECT_GT(cc.camera().position.z, 0.0f);
  cc.zoom(-2);
  EXPECT_GT(cc.camera().position.z, cc.camera().target.z);
}

TEST(ViewCamera, MoveLookAndReset) {
  CameraController cc;
  cc.setHome(start());
  cc.move(1, 0, 2);  // right is +x, forward is -z from (0,0,5) looking at the origin
  EXPECT_NEAR(cc.camera().position.x, 1.0f, 1e-5f);
  EXPECT_NEAR(cc.camera().position.z, 3.0f, 1e-5f);
  EXPECT_NEAR(cc.camera().target.z, -2.0f, 1e-5f);
  const glm::vec3 p = cc.camera().position;
  cc.look(50, 0);
  EXPECT_EQ(cc.camera().position, p);  // looking turns about the eye
  EXPECT_NEAR(glm::length(cc.camera().target - p), 5.0f, 1e-4f);
  cc.reset();
  EXPECT_EQ(cc.camera().position, start().position);
  EXPECT_EQ(cc.cameraArgument(), "0,0,5,0,0,0,50");
}

}  // namespace
}  // namespace rgraph::view
