# SchlierenPython.py, the ParaView Python plugin, generated from Plugin/Schlieren.xml and the
# Python package (Plugin/make_python_plugin.py) into <build>/lib/schlieren-python-plugin/ with
# libschlieren_engine.so.1 beside it: the folder a user copies to load it in another ParaView.
# Included by the top-level CMakeLists.txt.
find_program(SCHLIEREN_PLUGIN_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(SCHLIEREN_PLUGIN_PYTHON3)
  set(_pyplugin_dir "${CMAKE_BINARY_DIR}/lib/schlieren-python-plugin")
  file(GLOB _pyplugin_package "${PROJECT_SOURCE_DIR}/Python/schlieren/*.py")
  add_custom_command(
    OUTPUT "${_pyplugin_dir}/SchlierenPython.py"
    COMMAND "${CMAKE_COMMAND}" -E make_directory "${_pyplugin_dir}"
    COMMAND "${SCHLIEREN_PLUGIN_PYTHON3}" "${PROJECT_SOURCE_DIR}/Plugin/make_python_plugin.py"
      --xml "${PROJECT_SOURCE_DIR}/Plugin/Schlieren.xml"
      --package "${PROJECT_SOURCE_DIR}/Python/schlieren"
      --output "${_pyplugin_dir}/SchlierenPython.py"
      --view "${PROJECT_SOURCE_DIR}/Plugin/schlieren_view.py"
    COMMAND "${CMAKE_COMMAND}" -E copy "$<TARGET_FILE:schlieren_engine>"
      "${_pyplugin_dir}/$<TARGET_FILE_NAME:schlieren_engine>"
    DEPENDS "${PROJECT_SOURCE_DIR}/Plugin/make_python_plugin.py"
      "${PROJECT_SOURCE_DIR}/Plugin/schlieren_view.py"
      "${PROJECT_SOURCE_DIR}/Plugin/Schlieren.xml" ${_pyplugin_package} schlieren_engine
    COMMENT "Generating the ParaView Python plugin SchlierenPython.py")
  add_custom_target(SchlierenPythonPlugin ALL DEPENDS "${_pyplugin_dir}/SchlierenPython.py")
  set(SCHLIEREN_PYTHON_PLUGIN "${_pyplugin_dir}/SchlierenPython.py" CACHE INTERNAL "")
endif()
