# The patched ODE (scripts/build-ode.sh) as the imported target ode_bpp::ode.
set(_ode_lib "${ODE_ROOT}/lib/libode.so.8")
if(NOT EXISTS "${_ode_lib}" OR NOT EXISTS "${ODE_ROOT}/include/ode/mlcp.h")
  message(FATAL_ERROR "Patched ODE not found in ODE_ROOT='${ODE_ROOT}'.\n"
          "Build it with: scripts/build-ode.sh build patches   (or simply: make test)")
endif()
add_library(ode_bpp_ode SHARED IMPORTED GLOBAL)
set_target_properties(ode_bpp_ode PROPERTIES
  IMPORTED_LOCATION "${_ode_lib}"
  IMPORTED_SONAME "libode.so.8"
  INTERFACE_INCLUDE_DIRECTORIES "${ODE_ROOT}/include"
  INTERFACE_COMPILE_DEFINITIONS "dIDEDOUBLE")
add_library(ode_bpp::ode ALIAS ode_bpp_ode)
set(ODE_BPP_ODE_LIBDIR "${ODE_ROOT}/lib")
# binaries in the build tree find the patched libode, never Debian's
set(CMAKE_BUILD_RPATH "${ODE_BPP_ODE_LIBDIR};${CMAKE_BINARY_DIR}/ode_bpp")
set(CMAKE_INSTALL_RPATH "$ORIGIN/../lib")
