// What `rgraph render --stats` ("context") and `rgraph bench` (results.json's
// "machine") record of the GL context, against a context made in the test's
// own process: the same device choice, so the same strings.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "rgraph/gl/context.h"

namespace rgraph::test {

// The device a headless context of this process runs on (the CLI makes its own the same way).
inline ContextDevice thisProcessDevice() { return GlContext::create()->device(); }

inline void expectContextJson(const nlohmann::json& j, const ContextDevice& d) {
  SCOPED_TRACE(j.dump());
  EXPECT_EQ(j.at("vendor"), d.vendor);
  EXPECT_EQ(j.at("renderer"), d.renderer);
  EXPECT_EQ(j.at("version"), d.version);
  EXPECT_EQ(j.at("platform"), d.platform);
  if (d.eglDevice >= 0) {
    EXPECT_EQ(j.at("egl_device"), d.eglDevice);
    EXPECT_EQ(j.at("egl_device_description"), d.eglDeviceDescription);
  } else {
    EXPECT_TRUE(j.at("egl_device").is_null());
    EXPECT_TRUE(j.at("egl_device_description").is_null());
  }
}

}  // namespace rgraph::test
