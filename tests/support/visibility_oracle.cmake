# The exact-visibility oracle (issue 28: tests/support/visibility_oracle.h), a
# GL-free library for the test suites, the benchmarks and `rgraph bench`'s
# shadows axis. Included by tests/CMakeLists.txt, bench/CMakeLists.txt and
# apps/rgraph/CMakeLists.txt (any may be built alone).
if(NOT TARGET rgraph_visibility_oracle)
  find_package(Threads REQUIRED)
  add_library(rgraph_visibility_oracle STATIC
    ${CMAKE_CURRENT_LIST_DIR}/visibility_bvh.cpp
    ${CMAKE_CURRENT_LIST_DIR}/visibility_oracle.cpp)
  target_include_directories(rgraph_visibility_oracle PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(rgraph_visibility_oracle PUBLIC rgraph_scene glm::glm Threads::Threads)
endif()
