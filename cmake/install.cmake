# `cmake --install`: the libraries as the CMake package mbsopt (find_package(mbsopt CONFIG) gives each
# layer, mbsopt::linalg … mbsopt::design, and mbsopt::mbsopt for all of them), their headers under
# include/mbsopt/LAYER/, the `mbsopt` program, and the shipped scenes and
# design problems under share/mbsopt/. tests/consumer builds a program against the installed package.
include(CMakePackageConfigHelpers)

get_property(mbsopt_layers GLOBAL PROPERTY MBSOPT_LAYERS)
list(TRANSFORM mbsopt_layers PREPEND mbsopt_ OUTPUT_VARIABLE mbsopt_layer_targets)
add_library(mbsopt_all INTERFACE)
target_link_libraries(mbsopt_all INTERFACE ${mbsopt_layer_targets})
set_target_properties(mbsopt_all PROPERTIES EXPORT_NAME mbsopt)
add_library(mbsopt::mbsopt ALIAS mbsopt_all)

install(TARGETS mbsopt_eigen ${mbsopt_layer_targets} mbsopt_all
        EXPORT mbsoptTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS mbsopt RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(layer ${mbsopt_layers})
  get_target_property(layer_folder mbsopt_${layer} SOURCE_DIR)
  install(DIRECTORY ${layer_folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/mbsopt/${layer} FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/problems/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mbsopt/scenes
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/problems/suite/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mbsopt/suite
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.json" PATTERN "*.md")

set(MBSOPT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/mbsopt)
install(EXPORT mbsoptTargets NAMESPACE mbsopt:: DESTINATION ${MBSOPT_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mbsoptConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/mbsoptConfig.cmake INSTALL_DESTINATION ${MBSOPT_CMAKE_DIR})
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mbsoptConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mbsoptConfig.cmake ${PROJECT_BINARY_DIR}/mbsoptConfigVersion.cmake
        DESTINATION ${MBSOPT_CMAKE_DIR})
