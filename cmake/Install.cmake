# What `cmake --install` puts in place and what CPack packs (docs/install.md):
#   bin/parallax                        the CLI (statically linked to the module libraries)
#   lib/libparallax.so.0                every library module in one shared library
#   include/parallax/MODULE/*.h         their public headers (no third-party header among them:
#                                       the module_dependencies test keeps those in .cpp files
#                                       and a module's own *_internal.h, which are not installed)
#   lib/cmake/parallax/                 find_package(parallax) -> parallax::parallax
#   lib/pkgconfig/parallax.pc           pkg-config --cflags --libs parallax
#   share/doc/parallax/                 README, docs/, examples/ (examples/library: a consumer)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The modules the library is made of: all but the front ends (app: the CLI; python: the
# extension), their request layer (jobs: it runs a whole job, under mpirun too) and the
# process-level service it uses (cluster: MPI).
set(PARALLAX_LIBRARY_MODULES ${PARALLAX_MODULES})
list(REMOVE_ITEM PARALLAX_LIBRARY_MODULES app python jobs cluster)

set(library_archives "")
set(library_objects "")
foreach(module ${PARALLAX_LIBRARY_MODULES})
  get_target_property(type parallax_${module} TYPE)
  if(type STREQUAL "STATIC_LIBRARY")
    list(APPEND library_archives parallax_${module})
    list(APPEND library_objects "$<TARGET_OBJECTS:parallax_${module}>")
  endif()
endforeach()

# One shared library made of every (position-independent) object of the module archives, so
# that every symbol of every module is in it. Linking the archives as well brings in their
# third-party libraries, private to it (no archive member is pulled: the objects define all).
add_library(parallax_library SHARED "${CMAKE_CURRENT_LIST_DIR}/templates/library_version.cpp"
            ${library_objects})
target_link_libraries(parallax_library PRIVATE ${library_archives})
target_include_directories(parallax_library INTERFACE
  "$<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/src>" "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
target_compile_features(parallax_library INTERFACE cxx_std_20)
target_compile_definitions(parallax_library PRIVATE PARALLAX_VERSION="${PROJECT_VERSION}")
set_target_properties(parallax_library PROPERTIES
  OUTPUT_NAME parallax EXPORT_NAME parallax
  VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
  LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/lib")
add_library(parallax::parallax ALIAS parallax_library)

install(TARGETS parallax RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
install(TARGETS parallax_library EXPORT parallaxTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT library NAMELINK_COMPONENT development)
foreach(module ${PARALLAX_LIBRARY_MODULES})
  file(GLOB headers "${CMAKE_SOURCE_DIR}/src/parallax/${module}/*.h")
  list(FILTER headers EXCLUDE REGEX "_test_support\\.h$")
  list(FILTER headers EXCLUDE REGEX "_internal\\.h$")  # a module's own, third-party inside
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/parallax/${module}
          COMPONENT development)
endforeach()

set(PARALLAX_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/parallax)
install(EXPORT parallaxTargets NAMESPACE parallax:: DESTINATION ${PARALLAX_CMAKE_DIR}
        COMPONENT development)
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/templates/parallaxConfig.cmake.in"
  "${CMAKE_BINARY_DIR}/parallaxConfig.cmake" INSTALL_DESTINATION ${PARALLAX_CMAKE_DIR})
write_basic_package_version_file("${CMAKE_BINARY_DIR}/parallaxConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_BINARY_DIR}/parallaxConfig.cmake"
              "${CMAKE_BINARY_DIR}/parallaxConfigVersion.cmake"
        DESTINATION ${PARALLAX_CMAKE_DIR} COMPONENT development)

# pkg-config: paths relative to the .pc file, so a moved prefix still works.
file(RELATIVE_PATH PARALLAX_PC_PREFIX "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
configure_file("${CMAKE_CURRENT_LIST_DIR}/templates/parallax.pc.in"
               "${CMAKE_BINARY_DIR}/parallax.pc" @ONLY)
install(FILES "${CMAKE_BINARY_DIR}/parallax.pc" DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT development)

install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT documentation)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs COMPONENT documentation)
install(DIRECTORY examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
        COMPONENT documentation USE_SOURCE_PERMISSIONS)

# CPack: a Debian package whose dependencies dpkg-shlibdeps reads off the installed binaries,
# so they are the release's own runtime packages (libembree3-3 or libembree4-4, libtbb12,
# libavcodec59 or libavcodec61, ...), not the -dev ones the build needs.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME parallax)
set(CPACK_PACKAGE_VENDOR "parallax")
set(CPACK_PACKAGE_CONTACT "parallax developers <parallax@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Ray tracer for glasses-free 3-D displays (parallax barriers, lenticular panels)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python module is in the package when it was built; it needs numpy at import time, which
# no shared library says (an extension module links no libpython).
if(TARGET parallax_python)
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3 (>= 3.11), python3-numpy")
endif()
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DIRECTORY "${CMAKE_BINARY_DIR}/package")
include(CPack)
