# Installs the library as a CMake package: find_package(repose) then link repose::repose.
include(CMakePackageConfigHelpers)

install(TARGETS repose EXPORT reposeTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(REPOSE_HAVE_MPI)
  install(TARGETS repose_mpi EXPORT reposeTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/repose DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
else()
  install(DIRECTORY include/repose DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} PATTERN mpi_runner.hpp EXCLUDE)
endif()
if(TARGET repose_cli)
  # Component cli: `cmake --install <build> --component cli` installs only the tool (scripts/quickstart.sh).
  install(TARGETS repose_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
endif()

if(TARGET repose_c)
  # Component capi: the shared C library (the header is in include/repose) and the Fortran module's source,
  # which a Fortran program compiles with its own compiler (module files are compiler-specific).
  install(TARGETS repose_c LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT capi)
  install(FILES bindings/fortran/repose.f90 DESTINATION ${CMAKE_INSTALL_DATADIR}/repose/fortran COMPONENT capi)
endif()

set(REPOSE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/repose)
install(EXPORT reposeTargets NAMESPACE repose:: DESTINATION ${REPOSE_CMAKE_DIR})
configure_package_config_file(cmake/reposeConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/reposeConfig.cmake
  INSTALL_DESTINATION ${REPOSE_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/reposeConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/reposeConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/reposeConfigVersion.cmake
  DESTINATION ${REPOSE_CMAKE_DIR})
