# The wheel's compiler: Zig (PyPI's `ziglang`, a build requirement in pyproject.toml) as the C and
# C++ compiler for x86_64 Linux with glibc 2.28, so that libschlieren_engine.so asks for no symbol
# newer than GLIBC_2.28 and the wheel is manylinux_2_28 (RHEL 8 and its rebuilds, Ubuntu 20.04,
# Debian 10 and newer). Zig brings its own glibc stubs for the version named in the target and
# links LLVM's libc++ statically. docs/BUILDING.md says why this and not the system's GCC.
#
# Found through the Python that scikit-build-core runs CMake for (Python_EXECUTABLE, or
# SCHLIEREN_ZIG: the `zig` program itself). Where ziglang is not installed the system's compiler
# is used and the wheel's tag is whatever its glibc sets.
set(SCHLIEREN_ZIG_TARGET "x86_64-linux-gnu.2.28" CACHE STRING "Zig's -target for the wheel")
if(NOT SCHLIEREN_ZIG AND DEFINED ENV{SCHLIEREN_ZIG})
  set(SCHLIEREN_ZIG "$ENV{SCHLIEREN_ZIG}")
endif()
if(NOT SCHLIEREN_ZIG)
  foreach(_py IN ITEMS "${Python_EXECUTABLE}" "${Python3_EXECUTABLE}" "${PYTHON_EXECUTABLE}")
    if(_py AND NOT SCHLIEREN_ZIG)
      execute_process(COMMAND "${_py}" -c
        "import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), 'zig'))"
        OUTPUT_VARIABLE _zig OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _rc ERROR_QUIET)
      if(_rc EQUAL 0 AND EXISTS "${_zig}")
        set(SCHLIEREN_ZIG "${_zig}")
      endif()
    endif()
  endforeach()
endif()
if(SCHLIEREN_ZIG)
  set(SCHLIEREN_ZIG "${SCHLIEREN_ZIG}" CACHE FILEPATH "The zig program that compiles the engine")
  # CMake runs its compiler checks in projects of their own: hand them the same choice
  list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES SCHLIEREN_ZIG SCHLIEREN_ZIG_TARGET)
  set(CMAKE_C_COMPILER "${SCHLIEREN_ZIG}" cc -target ${SCHLIEREN_ZIG_TARGET})
  set(CMAKE_CXX_COMPILER "${SCHLIEREN_ZIG}" c++ -target ${SCHLIEREN_ZIG_TARGET})
  set(CMAKE_AR "${SCHLIEREN_ZIG}" CACHE FILEPATH "")
  # `zig ar` and `zig ranlib` through CMake's rule variables (CMAKE_AR is one program)
  set(CMAKE_C_ARCHIVE_CREATE "<CMAKE_AR> ar qc <TARGET> <LINK_FLAGS> <OBJECTS>")
  set(CMAKE_CXX_ARCHIVE_CREATE "<CMAKE_AR> ar qc <TARGET> <LINK_FLAGS> <OBJECTS>")
  set(CMAKE_C_ARCHIVE_FINISH "<CMAKE_AR> ranlib <TARGET>")
  set(CMAKE_CXX_ARCHIVE_FINISH "<CMAKE_AR> ranlib <TARGET>")
  set(SCHLIEREN_WHEEL_COMPILER "zig ${SCHLIEREN_ZIG_TARGET}")
else()
  message(WARNING "ziglang not found: the system's compiler builds the engine, and the wheel needs "
    "the glibc of this machine or newer (pip install ziglang, or SCHLIEREN_ZIG=/path/to/zig)")
endif()
