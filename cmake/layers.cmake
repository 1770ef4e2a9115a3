# mbsopt_add_layer(NAME SOURCES … [PUBLIC …] [PRIVATE …]): one layer of the library, from the sources
# of the folder that calls it: the static library mbsopt_NAME (mbsopt::NAME, installed as NAME), whose
# headers everyone includes as "mbsopt/NAME/FILE.hpp" — in the build tree through a link
# MBSOPT_INCLUDE_DIR/mbsopt/NAME to the folder, installed under include/mbsopt/NAME
# (cmake/install.cmake reads the layers from the global property MBSOPT_LAYERS, in pipeline order).
function(mbsopt_add_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 layer "" "" "SOURCES;PUBLIC;PRIVATE")
  add_library(mbsopt_${name} ${layer_SOURCES})
  target_include_directories(mbsopt_${name} PUBLIC $<BUILD_INTERFACE:${MBSOPT_INCLUDE_DIR}>
                                                   $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(mbsopt_${name} PUBLIC ${layer_PUBLIC} PRIVATE ${layer_PRIVATE})
  set_target_properties(mbsopt_${name} PROPERTIES EXPORT_NAME ${name})
  add_library(mbsopt::${name} ALIAS mbsopt_${name})
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR} ${MBSOPT_INCLUDE_DIR}/mbsopt/${name} SYMBOLIC)
  set_property(GLOBAL APPEND PROPERTY MBSOPT_LAYERS ${name})
endfunction()
