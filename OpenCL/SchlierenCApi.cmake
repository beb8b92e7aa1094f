# libschlieren_engine.so: the engine and its C interface (schlieren_c.h), exporting nothing but
# the schlieren_* functions (a version script), libstdc++ linked in where SCHLIEREN_STATIC_LIBSTDCXX
# is on (the wheel: it then needs only glibc of the system). Included by OpenCL/CMakeLists.txt.
option(SCHLIEREN_STATIC_LIBSTDCXX "Link libstdc++ and libgcc statically into libschlieren_engine" OFF)
add_library(schlieren_engine SHARED "${CMAKE_CURRENT_LIST_DIR}/SchlierenCApi.cxx")
target_include_directories(schlieren_engine PUBLIC "${CMAKE_CURRENT_LIST_DIR}")
target_link_libraries(schlieren_engine PRIVATE SchlierenEngine)
set_target_properties(schlieren_engine PROPERTIES
  C_VISIBILITY_PRESET hidden CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
  VERSION 1 SOVERSION 1)
set(_schlieren_map "${CMAKE_CURRENT_BINARY_DIR}/schlieren_engine.map")
file(WRITE "${_schlieren_map}" "{ global: schlieren_*; local: *; };\n")
target_link_options(schlieren_engine PRIVATE "LINKER:--version-script=${_schlieren_map}"
  "LINKER:--no-undefined")
if(NOT SCHLIEREN_ZIG) # Zig's linker has no --exclude-libs; the version script hides them there
  target_link_options(schlieren_engine PRIVATE "LINKER:--exclude-libs,ALL")
endif()
set_property(TARGET schlieren_engine APPEND PROPERTY LINK_DEPENDS "${_schlieren_map}")
if(SCHLIEREN_STATIC_LIBSTDCXX AND NOT SCHLIEREN_ZIG) # Zig links its libc++ statically anyway
  target_link_options(schlieren_engine PRIVATE -static-libstdc++ -static-libgcc)
endif()
# a Python wheel (scikit-build-core, pyproject.toml): the library beside the package's modules
if(SKBUILD)
  install(TARGETS schlieren_engine LIBRARY DESTINATION schlieren NAMELINK_SKIP COMPONENT python)
endif()
# `cmake --install`: the library, its header and a pkg-config file for C and other front ends
# (component development; the wheel installs only component python)
if(NOT SKBUILD)
  include(GNUInstallDirs)
  install(TARGETS schlieren_engine LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    COMPONENT development)
  install(FILES "${CMAKE_CURRENT_LIST_DIR}/schlieren_c.h"
    DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/schlieren" COMPONENT development)
  # relocatable: the prefix from the .pc file's own folder
  file(RELATIVE_PATH _schlieren_pc_to_prefix "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/schlieren_engine.pc"
    "prefix=\${pcfiledir}/${_schlieren_pc_to_prefix}\n"
    "libdir=\${prefix}/${CMAKE_INSTALL_LIBDIR}\n"
    "includedir=\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}/schlieren\n\n"
    "Name: schlieren_engine\n"
    "Description: Schlieren's VTK-free ray-tracing engine, C interface (schlieren_c.h)\n"
    "Version: 0.1.0\n"
    "Libs: -L\${libdir} -lschlieren_engine\n"
    "Cflags: -I\${includedir}\n")
  install(FILES "${CMAKE_CURRENT_BINARY_DIR}/schlieren_engine.pc"
    DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig" COMPONENT development)
endif()
# the C interface from C, with no OpenCL loader to be found (the CPU fallback)
if(BUILD_TESTING)
  enable_language(C)
  add_executable(TestCApi "${PROJECT_SOURCE_DIR}/Testing/Cxx/TestCApi.c")
  find_package(Threads REQUIRED)
  target_link_libraries(TestCApi PRIVATE schlieren_engine m Threads::Threads)
  add_test(NAME engine.TestCApi COMMAND TestCApi)
  # the hashes of a few images, to compare builds (scripts/windows-engine.sh)
  add_executable(SchlierenTraceHash "${PROJECT_SOURCE_DIR}/Testing/Cxx/SchlierenTraceHash.c")
  target_link_libraries(SchlierenTraceHash PRIVATE schlieren_engine)
  set_tests_properties(engine.TestCApi PROPERTIES LABELS engine
    ENVIRONMENT "SCHLIEREN_OPENCL_LIBRARY=/nonexistent/libOpenCL.so.1")
  # the C interface fuzzed (issue 48): the crashers as named cases, then 4000 seeded random calls
  # (a few seconds); the long run under AddressSanitizer: docs/FUZZING.md
  find_package(Threads REQUIRED)
  add_executable(TestCApiFuzz "${PROJECT_SOURCE_DIR}/Testing/Cxx/TestCApiFuzz.c")
  target_link_libraries(TestCApiFuzz PRIVATE schlieren_engine m Threads::Threads)
  add_test(NAME engine.TestCApiFuzz COMMAND TestCApiFuzz --cases 4000 --seed 48)
  set_tests_properties(engine.TestCApiFuzz PROPERTIES LABELS engine TIMEOUT 300
    ENVIRONMENT "SCHLIEREN_OPENCL_LIBRARY=/nonexistent/libOpenCL.so.1")
endif()
