# rgraph_add_plugin(<name> SOURCES <file>... [SHADERS <file>...] [NO_INSTALL]
#                   [OUTPUT_ROOT <dir>])
#
# Builds a pass plugin: a MODULE library librgraph_<name>.so in
# <build>/lib/rgraph/plugins, linked to rgraph::rgraph, with its shaders
# copied to <build>/share/rgraph/plugins/<name>/ (where PluginHost::shaderPath
# finds them), and install rules that put both in the same places under the
# install prefix. The same function serves the rgraph tree (plugins/) and
# out-of-tree plugins (find_package(rgraph) provides it).
#
# The target is called <name>; shaders are copied flat (by file name). Beside
# the copies, rgraph-shader-sources.txt maps each copy to the file it was
# copied from, so that shader errors name the file to edit (rgraph/shader_check.h,
# shaderOrigin); it is not installed. OUTPUT_ROOT puts the library and the
# shaders under <dir>/lib/... and <dir>/share/... instead of the build
# folder's (test plugins kept apart from the real ones).
include_guard(GLOBAL)
include(GNUInstallDirs)

function(rgraph_add_plugin name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "NO_INSTALL" "OUTPUT_ROOT" "SOURCES;SHADERS")
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "rgraph_add_plugin(${name}): no SOURCES")
  endif()
  set(root "${CMAKE_BINARY_DIR}")
  if(ARG_OUTPUT_ROOT)
    set(root "${ARG_OUTPUT_ROOT}")
  endif()
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE rgraph::rgraph)
  set_target_properties(${name} PROPERTIES
    PREFIX "lib"
    OUTPUT_NAME "rgraph_${name}"
    LIBRARY_OUTPUT_DIRECTORY "${root}/lib/rgraph/plugins"
    CXX_VISIBILITY_PRESET hidden       # only the RGRAPH_PLUGIN entry points are exported
    VISIBILITY_INLINES_HIDDEN ON
    INSTALL_RPATH "$ORIGIN/../..")     # <libdir>/rgraph/plugins -> <libdir> (librgraph.so)

  set(shader_dir "${root}/share/rgraph/plugins/${name}")
  set(copies)
  set(sources)
  set(manifest "# Written by rgraph_add_plugin(${name}): each shader copied here and the file it is a copy of.\n")
  foreach(shader IN LISTS ARG_SHADERS)
    get_filename_component(src "${shader}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_filename_component(file "${shader}" NAME)
    add_custom_command(OUTPUT "${shader_dir}/${file}"
      COMMAND ${CMAKE_COMMAND} -E make_directory "${shader_dir}"
      COMMAND ${CMAKE_COMMAND} -E copy_if_different "${src}" "${shader_dir}/${file}"
      DEPENDS "${src}" COMMENT "rgraph plugin ${name}: shader ${file}" VERBATIM)
    list(APPEND copies "${shader_dir}/${file}")
    list(APPEND sources "${src}")
    string(APPEND manifest "${file}\t${src}\n")
  endforeach()
  if(copies)
    file(GENERATE OUTPUT "${shader_dir}/rgraph-shader-sources.txt" CONTENT "${manifest}")
    add_custom_target(${name}_shaders DEPENDS ${copies})
    add_dependencies(${name} ${name}_shaders)
  endif()

  if(NOT ARG_NO_INSTALL)
    install(TARGETS ${name} LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}/rgraph/plugins")
    if(sources)
      install(FILES ${sources} DESTINATION "${CMAKE_INSTALL_DATADIR}/rgraph/plugins/${name}")
    endif()
  endif()
endfunction()
