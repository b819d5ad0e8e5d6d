# SPDX-License-Identifier: Apache-2.0
# Run by `cmake --install` (CMakeLists.txt's install(CODE)): fills in
# libisect/isect.pc.in for the prefix being installed to and installs the
# result as LIBDIR/pkgconfig/isect.pc (DESTDIR is honoured by file(INSTALL)).
set(PREFIX "${CMAKE_INSTALL_PREFIX}")
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${ISECT_PC_${_dir}}")
    set(${_dir} "${ISECT_PC_${_dir}}")
  else()
    set(${_dir} "${CMAKE_INSTALL_PREFIX}/${ISECT_PC_${_dir}}")
  endif()
endforeach()
set(VERSION "${ISECT_PC_VERSION}")
configure_file("${ISECT_PC_TEMPLATE}" "${ISECT_PC_OUTPUT}" @ONLY)
file(INSTALL DESTINATION "${LIBDIR}/pkgconfig" TYPE FILE FILES "${ISECT_PC_OUTPUT}")
