# Install the library, headers, CLI and a package config so that find_package(stiffpath) works.
include(CMakePackageConfigHelpers)
install(TARGETS stiffpath stiffpath_warnings EXPORT stiffpathTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS stiffpath_vision EXPORT stiffpathVisionTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT stiffpathVisionTargets NAMESPACE stiffpath:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiffpath)
install(TARGETS stiffpath_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS stiffpath_vision_cli RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/stiffpath)
# Installed programs and libraries find the shared libraries relative to themselves, so a prefix can be moved.
file(RELATIVE_PATH bin_to_lib /prefix/${CMAKE_INSTALL_BINDIR} /prefix/${CMAKE_INSTALL_LIBDIR})
file(RELATIVE_PATH libexec_to_lib /prefix/${CMAKE_INSTALL_LIBEXECDIR}/stiffpath /prefix/${CMAKE_INSTALL_LIBDIR})
set_target_properties(stiffpath_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${bin_to_lib}")
set_target_properties(stiffpath_vision_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${libexec_to_lib}")
set_target_properties(stiffpath_vision PROPERTIES INSTALL_RPATH "$ORIGIN")
if(TARGET stiffpath_halstream)
  set_target_properties(stiffpath_halstream PROPERTIES INSTALL_RPATH "$ORIGIN/${bin_to_lib}")
endif()
install(DIRECTORY include/stiffpath DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/stiffpath)
install(EXPORT stiffpathTargets NAMESPACE stiffpath:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiffpath)
configure_package_config_file(cmake/stiffpathConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/stiffpathConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiffpath)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/stiffpathConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/stiffpathConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/stiffpathConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stiffpath)
