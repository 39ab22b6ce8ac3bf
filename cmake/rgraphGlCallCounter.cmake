# rgraph_count_gl_calls(target): `target` counts the GL calls it makes, its own
# and those of librgraph, the passes and plugins it loads
# (bench/gl_call_counter.h): every GL entry point the sources name is defined
# in the program as a counting trampoline, exported so that the shared
# libraries bind to it too. The list of entry points is rebuilt when a source
# changes. Used by the overhead benchmark and by the GL-call tests.
function(rgraph_count_gl_calls target)
  find_file(RGRAPH_GLCOREARB_H GL/glcorearb.h REQUIRED)
  file(GLOB_RECURSE callers CONFIGURE_DEPENDS
    ${CMAKE_SOURCE_DIR}/core/*.cpp ${CMAKE_SOURCE_DIR}/core/*.h
    ${CMAKE_SOURCE_DIR}/passes/*.cpp ${CMAKE_SOURCE_DIR}/passes/*.h
    ${CMAKE_SOURCE_DIR}/plugins/*.cpp ${CMAKE_SOURCE_DIR}/plugins/*.h
    ${CMAKE_SOURCE_DIR}/bench/render_*.cpp ${CMAKE_SOURCE_DIR}/tests/gl_calls/*.cpp)
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_gl_entry_points)
  set(list ${dir}/gl_entry_points.inc)
  add_custom_command(OUTPUT ${list}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${dir}
    COMMAND ${CMAKE_COMMAND} -DHEADER=${RGRAPH_GLCOREARB_H} -DOUT=${list}
      "-DSOURCES=${callers}" -P ${CMAKE_SOURCE_DIR}/bench/gl_entry_points.cmake
    DEPENDS ${callers} ${CMAKE_SOURCE_DIR}/bench/gl_entry_points.cmake
    COMMENT "Listing the GL entry points rgraph calls (${target})" VERBATIM)
  target_sources(${target} PRIVATE ${CMAKE_SOURCE_DIR}/bench/gl_call_counter.cpp ${list})
  set_source_files_properties(${CMAKE_SOURCE_DIR}/bench/gl_call_counter.cpp PROPERTIES OBJECT_DEPENDS ${list})
  target_compile_definitions(${target} PRIVATE RGRAPH_GL_ENTRY_POINTS)
  target_include_directories(${target} PRIVATE ${dir} ${CMAKE_SOURCE_DIR}/bench)
  target_link_libraries(${target} PRIVATE ${CMAKE_DL_LIBS})
  set_target_properties(${target} PROPERTIES ENABLE_EXPORTS ON)
endfunction()
