# `cmake --install BUILD [--prefix DIR]`: the aavio command, every module's static library and
# headers, and a CMake package, so that a program uses the library with
#   find_package(aavio REQUIRED)
#   target_link_libraries(my_program PRIVATE aavio::aavio)   # or single modules: aavio::pipeline
# (examples/ holds such programs; docs/api.md is the guide).
include(CMakePackageConfigHelpers)

# aavio::aavio: every module.
get_property(aavio_libraries GLOBAL PROPERTY AAVIO_LIBRARIES)
add_library(aavio_all INTERFACE)
add_library(aavio::aavio ALIAS aavio_all)
set_target_properties(aavio_all PROPERTIES EXPORT_NAME aavio)
target_link_libraries(aavio_all INTERFACE ${aavio_libraries})

install(TARGETS aavio_all EXPORT aavioTargets)
install(TARGETS aavio RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/aavio DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/aavio)
install(EXPORT aavioTargets NAMESPACE aavio:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/aavioConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/aavioConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/aavioConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/aavioConfig.cmake ${PROJECT_BINARY_DIR}/aavioConfigVersion.cmake
        DESTINATION ${config_dir})
