# Install rules and the relocatable CMake package for the header-only cellforge target.
# Consumers write `find_package(cellforge CONFIG REQUIRED)` and link `cellforge::cellforge`, or
# `find_package(cellforge CONFIG REQUIRED COMPONENTS sketch)` and link `cellforge::sketch` (+ Eigen).
include(CMakePackageConfigHelpers)

# Arch-independent: the package holds only headers and CMake files, so it goes under share/.
set(CELLFORGE_INSTALL_CMAKEDIR "${CMAKE_INSTALL_DATADIR}/cmake/cellforge"
    CACHE STRING "Where the cellforge CMake package files are installed (relative to the prefix)")
mark_as_advanced(CELLFORGE_INSTALL_CMAKEDIR)

install(TARGETS cellforge EXPORT cellforge-targets)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
        FILES_MATCHING PATTERN "*.hpp")
install(EXPORT cellforge-targets NAMESPACE cellforge:: DESTINATION "${CELLFORGE_INSTALL_CMAKEDIR}")
# The sketch target in a file of its own, read only when the consumer asks for the component: its
# link to Eigen3::Eigen must not make every consumer look for Eigen.
if(TARGET cellforge_sketch)
  install(TARGETS cellforge_sketch EXPORT cellforge-sketch-targets)
  install(EXPORT cellforge-sketch-targets NAMESPACE cellforge:: DESTINATION "${CELLFORGE_INSTALL_CMAKEDIR}")
endif()

configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/cellforge-config.cmake.in"
  "${PROJECT_BINARY_DIR}/cellforge-config.cmake" INSTALL_DESTINATION "${CELLFORGE_INSTALL_CMAKEDIR}")
# Before 1.0 a minor release may break the API, so 0.x accepts only the same minor version.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(_cellforge_compat SameMinorVersion)
else()
  set(_cellforge_compat SameMajorVersion)
endif()
write_basic_package_version_file("${PROJECT_BINARY_DIR}/cellforge-config-version.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY ${_cellforge_compat} ARCH_INDEPENDENT)
unset(_cellforge_compat)
install(FILES "${PROJECT_BINARY_DIR}/cellforge-config.cmake" "${PROJECT_BINARY_DIR}/cellforge-config-version.cmake"
        DESTINATION "${CELLFORGE_INSTALL_CMAKEDIR}")
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION "${CMAKE_INSTALL_DATADIR}/doc/cellforge")
