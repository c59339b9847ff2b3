# laguerre_library(FOLDER [PUBLIC deps…] [PRIVATE deps…]): the library of one top-level folder, the same
# shape for all four: laguerre_<FOLDER> from <FOLDER>/src/**/*.cpp, public headers in <FOLDER>/include,
# the alias laguerre::<FOLDER>, exported as laguerre::<FOLDER>; our warning and sanitizer flags
# (laguerre_options) apply inside the build tree only.
function(laguerre_library folder)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(laguerre_${folder} ${sources})
  add_library(laguerre::${folder} ALIAS laguerre_${folder})
  set_target_properties(laguerre_${folder} PROPERTIES EXPORT_NAME ${folder})
  target_include_directories(laguerre_${folder} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  target_link_libraries(laguerre_${folder} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE} $<BUILD_INTERFACE:laguerre_options>)
endfunction()
