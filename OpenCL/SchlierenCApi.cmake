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
  "LINKER:--exclude-libs,ALL" "LINKER:--no-undefined")
set_property(TARGET schlieren_engine APPEND PROPERTY LINK_DEPENDS "${_schlieren_map}")
if(SCHLIEREN_STATIC_LIBSTDCXX)
  target_link_options(schlieren_engine PRIVATE -static-libstdc++ -static-libgcc)
endif()
# a Python wheel (scikit-build-core, pyproject.toml): the library beside the package's modules
if(SKBUILD)
  install(TARGETS schlieren_engine LIBRARY DESTINATION schlieren NAMELINK_SKIP COMPONENT python)
endif()
# the C interface from C, with no OpenCL loader to be found (the CPU fallback)
if(BUILD_TESTING)
  enable_language(C)
  add_executable(TestCApi "${PROJECT_SOURCE_DIR}/Testing/Cxx/TestCApi.c")
  target_link_libraries(TestCApi PRIVATE schlieren_engine m)
  add_test(NAME engine.TestCApi COMMAND TestCApi)
  set_tests_properties(engine.TestCApi PROPERTIES LABELS engine
    ENVIRONMENT "SCHLIEREN_OPENCL_LIBRARY=/nonexistent/libOpenCL.so.1")
endif()
