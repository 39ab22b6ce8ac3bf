# Precompiled headers for the test programs (tests/CMakeLists.txt). Measured
# on these 2-core machines (README, "Set up"): a test source spends 0.5-1 s of
# its 4-9 s in GoogleTest, nlohmann-json, GLM and the standard headers, which
# a PCH saves; a library source saves nothing (its time is code generation),
# and the libraries' PCH made `--target rgraph_cli` 19% slower, so they have
# none. GCC takes a PCH only where the flags match, -fPIE against -fPIC
# included: one stub executable (rgraph_test_pch) compiles it and every test
# program reuses it. -DRGRAPH_PCH=OFF compiles every source on its own
# includes: the sanitizer and fuzz builds do, so that CI still sees a test
# that forgets an include.
option(RGRAPH_PCH "Precompile the headers the test programs share" ON)

set(RGRAPH_TEST_PCH_HEADERS
  <gtest/gtest.h> <nlohmann/json.hpp> <glm/glm.hpp> <glm/gtc/matrix_transform.hpp>
  <algorithm> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <functional> <map> <memory> <optional> <set>
  <sstream> <string> <vector>)
