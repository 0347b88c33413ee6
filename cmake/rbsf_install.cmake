# The installed package: `cmake --install build --prefix P` puts the headers under
# P/include/rbsf, the libraries under P/lib, the tools under P/bin and the CMake package
# under P/lib/cmake/rbsf, so that find_package(rbsf [COMPONENTS ...]) (with P in
# CMAKE_PREFIX_PATH) gives rbsf::dynamics, rbsf::plan, rbsf::trajopt, rbsf::executor,
# rbsf::planner and rbsf::controller. Every path in it is relative to P: the tree may be moved.
include(CMakePackageConfigHelpers)
set(RBSF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rbsf)

get_target_property(_rbsf_kind rbsf_dynamics TYPE)
if(_rbsf_kind STREQUAL "STATIC_LIBRARY")
  set(RBSF_LIBRARY_KIND "static")
else()
  set(RBSF_LIBRARY_KIND "shared")
endif()
# Libraries and their headers (one include/ folder per module), each module its own export
# set (rbsf_<module>Targets.cmake), so that find_package(rbsf COMPONENTS ...) loads only
# what was asked for (rbsfConfig.cmake.in).
set(_rbsf_modules dynamics plan trajopt executor planner controller)
foreach(_module IN LISTS _rbsf_modules)
  install(TARGETS rbsf_${_module} EXPORT rbsf_${_module}Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_module}/include/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT rbsf_${_module}Targets NAMESPACE rbsf:: DESTINATION ${RBSF_CMAKE_DIR})
endforeach()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rbsfConfig.cmake.in
  ${PROJECT_BINARY_DIR}/rbsfConfig.cmake INSTALL_DESTINATION ${RBSF_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rbsfConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rbsfConfig.cmake ${PROJECT_BINARY_DIR}/rbsfConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/rbsf_ompl.cmake
        DESTINATION ${RBSF_CMAKE_DIR})
install(TARGETS rbsf-analyze plan-reorientation rbsf-simulate rbsf-replay
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/cells/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rbsf/cells)
