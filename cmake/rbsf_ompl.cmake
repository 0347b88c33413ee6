# rbsf::ompl: an imported interface target for OMPL, whose Debian package (1.5.2) defines
# only OMPL_INCLUDE_DIRS and OMPL_LIBRARIES. Included by planner/CMakeLists.txt and by the
# installed rbsfConfig.cmake: both resolve OMPL on the machine at hand, so the exported
# rbsf::planner refers to the target by name and the install tree stays relocatable.
if(NOT TARGET rbsf::ompl)
  if(NOT OMPL_LIBRARIES)
    find_package(ompl REQUIRED)
  endif()
  add_library(rbsf::ompl INTERFACE IMPORTED)
  set_target_properties(rbsf::ompl PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIRS}"
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
endif()
