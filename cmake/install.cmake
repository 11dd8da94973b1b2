# Installs the library side of stiction for other projects: the static libraries core,
# components, scene, io (and sys, which io uses), the services under the command line (run,
# check, study, sweep, compare, verify; with what they link: plot, image, text and the render
# settings), their headers under include/stiction/, and a CMake package (find_package(stiction)
# -> stiction::stiction, stiction::services). The command-line program, the render plugin and
# the data (scenes, assets) are installed by their own directories; the binary and the Python
# module find them relative to themselves (src/sys/data_dirs.hpp), so the prefix can be moved.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(STICTION_EXPORTED stiction_sys stiction_core stiction_components stiction_scene stiction_io
                      stiction_image stiction_text stiction_plot stiction_render_settings
                      stiction_services)
foreach(target ${STICTION_EXPORTED})
  string(REPLACE "stiction_" "" short ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${short})
endforeach()

# One target for all of them.
add_library(stiction_all INTERFACE)
target_link_libraries(stiction_all INTERFACE stiction_core stiction_components stiction_scene stiction_io)
set_target_properties(stiction_all PROPERTIES EXPORT_NAME stiction)
set_target_properties(stiction_warnings PROPERTIES EXPORT_NAME warnings)

install(TARGETS ${STICTION_EXPORTED} stiction_all stiction_warnings
        EXPORT stictionTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stiction)
foreach(dir core components scene io sys image text plot render services)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stiction
          FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(EXPORT stictionTargets NAMESPACE stiction:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiction)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/stictionConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/stictionConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiction)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/stictionConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/stictionConfig.cmake ${PROJECT_BINARY_DIR}/stictionConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiction)
