# Installable package: find_package(ode_bpp) + target_link_libraries(app ode_bpp::ode_bpp),
# and a pkg-config file. The patched libode (same soname as Debian's libode8) is installed
# beside libode_bpp so that an app gets both from one prefix.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS ode_bpp EXPORT ode_bppTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/ode_bpp/include/ode_bpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# ODE_BPP_API, generated with the library (ode_bpp/CMakeLists.txt)
install(FILES ${CMAKE_BINARY_DIR}/ode_bpp/include/ode_bpp/export.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ode_bpp)
install(DIRECTORY ${ODE_ROOT}/include/ode DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${ODE_ROOT}/lib/libode.so.8.0.2 ${ODE_ROOT}/lib/libode.so.8 ${ODE_ROOT}/lib/libode.so
  DESTINATION ${CMAKE_INSTALL_LIBDIR})

# ode_bpp's link interface names ode_bpp::libode once installed (ode_bpp/CMakeLists.txt);
# the config file recreates that imported target relative to the install prefix
install(EXPORT ode_bppTargets NAMESPACE ode_bpp:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ode_bpp)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/ode_bppConfig.cmake.in
  ${CMAKE_BINARY_DIR}/ode_bppConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ode_bpp)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/ode_bppConfigVersion.cmake COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/ode_bppConfig.cmake ${CMAKE_BINARY_DIR}/ode_bppConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ode_bpp)

# relocatable: the prefix is found relative to the .pc file itself
file(RELATIVE_PATH ODE_BPP_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
configure_file(${CMAKE_SOURCE_DIR}/cmake/ode_bpp.pc.in ${CMAKE_BINARY_DIR}/ode_bpp.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/ode_bpp.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
