# Install rules and the exported CMake package:
#   bin/rgraph                                  the command line
#   <libdir>/librgraph.so                       the library (graph, GL backend, built-in passes)
#   <libdir>/rgraph/plugins/librgraph_*.so      plugins (rgraph_add_plugin)
#   include/rgraph/**                           public headers (with gl/, and passes/ from passes/common)
#   share/rgraph/shaders/**                     built-in shaders
#   share/rgraph/plugins/<name>/                plugin shaders (rgraph_add_plugin)
#   share/rgraph/pipelines/**                   pipelines (`rgraph render` finds default.json here)
#   <libdir>/cmake/rgraph/                      rgraphConfig.cmake, targets, rgraph_add_plugin
include(CMakePackageConfigHelpers)
set(RGRAPH_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rgraph)

set_target_properties(rgraph_cli PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
install(TARGETS rgraph_lib EXPORT rgraphTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS rgraph_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/rgraph DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/passes/common/include/rgraph DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/ DESTINATION ${RGRAPH_SHADER_INSTALL_DIR})
set(RGRAPH_PIPELINE_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/rgraph/pipelines)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/pipelines/ DESTINATION ${RGRAPH_PIPELINE_INSTALL_DIR}
  FILES_MATCHING PATTERN "*.json")

install(EXPORT rgraphTargets NAMESPACE rgraph:: DESTINATION ${RGRAPH_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rgraphConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/rgraphConfig.cmake
  INSTALL_DESTINATION ${RGRAPH_CMAKE_INSTALL_DIR}
  PATH_VARS RGRAPH_PLUGIN_INSTALL_DIR RGRAPH_SHADER_INSTALL_DIR RGRAPH_PIPELINE_INSTALL_DIR CMAKE_INSTALL_BINDIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/rgraphConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/rgraphConfig.cmake ${CMAKE_BINARY_DIR}/cmake/rgraphConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/rgraphPlugin.cmake
  DESTINATION ${RGRAPH_CMAKE_INSTALL_DIR})
