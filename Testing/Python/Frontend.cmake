# The Python front end (Python/schlieren over libschlieren_engine) in venvs with PyPI's vtk: the
# newest 9.x and the oldest the package claims (9.2), each against the C++ plugin's images.
# Included by Testing/Python/CMakeLists.txt (it defines _pvpython, _plugin, _python, _env).
#   ctest -R python.frontend
# The venvs and the pip cache stay in <build>/python-venvs: the wheels are downloaded once per
# build tree. Skipped (77) where PyPI cannot be reached.
set(SCHLIEREN_FRONTEND_VTK_NEWEST "vtk==9.7.2 numpy pyvista" CACHE STRING
  "Requirements of the newest-vtk venv of the python.frontend tests (PyVista: the example)")
set(SCHLIEREN_FRONTEND_VTK_OLDEST "vtk==9.2.6 numpy<2" CACHE STRING
  "Requirements of the oldest-vtk venv of the python.frontend tests")
set(_frontend_ref "${CMAKE_CURRENT_BINARY_DIR}/Temporary/frontend_reference")
set(_venvs "${CMAKE_BINARY_DIR}/python-venvs")
# (RefractiveIndex's matrix reads two of the suite's solved OpenFOAM cases: schlieren_openfoam)
schlieren_python_test(frontend_reference
  COMMAND "${_pvpython}" "${_here}/frontend_reference.py" --plugin "${_plugin}"
    --output "${_frontend_ref}" --openfoam "${CMAKE_BINARY_DIR}/openfoam"
  PROPERTIES FIXTURES_SETUP frontend_reference FIXTURES_REQUIRED schlieren_openfoam)
foreach(_which NEWEST OLDEST)
  string(TOLOWER "${_which}" _lower)
  schlieren_python_test(frontend_vtk_${_lower}
    COMMAND "${_python}" "${_here}/frontend_venv.py" --venv "${_venvs}/vtk-${_lower}"
      --requirements "${SCHLIEREN_FRONTEND_VTK_${_which}}"
      --pythonpath "${PROJECT_SOURCE_DIR}/Python"
      -- "${_here}/test_frontend.py" --reference "${_frontend_ref}"
    TIMEOUT 900
    PROPERTIES FIXTURES_REQUIRED frontend_reference SKIP_RETURN_CODE 77
      RESOURCE_LOCK python_venvs)
  set_property(TEST python.frontend_vtk_${_lower} APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
  # inputs and errors in plain VTK: a multiblock to RefractiveIndex gives one image, the C++
  # SchlierenImage's refusals, an extent not starting at 0, no image left by a failed request
  schlieren_python_test(frontend_inputs_vtk_${_lower}
    COMMAND "${_python}" "${_here}/frontend_venv.py" --venv "${_venvs}/vtk-${_lower}"
      --requirements "${SCHLIEREN_FRONTEND_VTK_${_which}}"
      --pythonpath "${PROJECT_SOURCE_DIR}/Python"
      -- "${_here}/test_frontend_inputs.py"
    TIMEOUT 900
    PROPERTIES SKIP_RETURN_CODE 77 RESOURCE_LOCK python_venvs)
  set_property(TEST python.frontend_inputs_vtk_${_lower} APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
endforeach()

# the examples, in the newest venv (PyVista from PyPI there)
foreach(_example pyvista_jet numpy_lens)
  schlieren_python_test(frontend_example_${_example}
    COMMAND "${_python}" "${_here}/frontend_venv.py" --venv "${_venvs}/vtk-newest"
      --requirements "${SCHLIEREN_FRONTEND_VTK_NEWEST}"
      --pythonpath "${PROJECT_SOURCE_DIR}/Python"
      -- "${PROJECT_SOURCE_DIR}/Examples/${_example}.py" --output "${_temp}/${_example}.png"
    TIMEOUT 900
    PROPERTIES SKIP_RETURN_CODE 77 RESOURCE_LOCK python_venvs)
  set_property(TEST python.frontend_example_${_example} APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
endforeach()

# pip wheel . -> auditwheel -> a fresh venv with no build tree: imports, demo, the same image
schlieren_python_test(frontend_wheel
  COMMAND "${_python}" "${_here}/test_wheel.py" --source "${PROJECT_SOURCE_DIR}"
    --work "${_venvs}/wheel" --reference-library "$<TARGET_FILE:schlieren_engine>"
  TIMEOUT 1500
  PROPERTIES SKIP_RETURN_CODE 77 PROCESSORS 2)

# the C interface's property table (the Python package's keywords and defaults) against
# Plugin/Schlieren.xml: names, sizes, defaults, entries (Debian's Python with NumPy, no venv)
schlieren_python_test(frontend_properties
  COMMAND "${_python}" "${_here}/test_frontend_properties.py"
    --xml "${PROJECT_SOURCE_DIR}/Plugin/Schlieren.xml")
# the package from the source tree (not the plugin's compiled `schlieren` of the other tests)
set_property(TEST python.frontend_properties PROPERTY ENVIRONMENT
  "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>"
  "PYTHONPATH=${PROJECT_SOURCE_DIR}/Python")

# the ParaView Python plugin (generated SchlierenPython.py) in Debian's pvpython: property lists
# and defaults against Schlieren.xml, images against the C++ plugin's
if(SCHLIEREN_PYTHON_PLUGIN)
  schlieren_python_test(python_plugin
    COMMAND "${_pvpython}" "${_here}/test_python_plugin.py" --plugin "${SCHLIEREN_PYTHON_PLUGIN}"
      --xml "${PROJECT_SOURCE_DIR}/Plugin/Schlieren.xml" --reference "${_frontend_ref}"
      --package "${PROJECT_SOURCE_DIR}/Python"
    PROPERTIES FIXTURES_REQUIRED frontend_reference)
  # the Python front end's package beside the C++ plugin's schlieren_vtk, in one session
  set_property(TEST python.python_plugin APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
  # where a user meets it, against the C++ plugin's compiled filters in the same pvpython: one
  # vtkImageData for any input (the blunt fin's multiblock), errors as VTK errors with an empty
  # output (no traceback), NumericalSchlieren's update extent, schlieren_view embedded
  # (Examples/first_light.py), the C++ filter's refusals and an extent not starting at 0;
  # RefractiveIndex's parity matrix (frontend_cases.INDEX) against the reference run's records;
  # NumericalSchlieren's progress and abort
  schlieren_python_test(python_plugin_parity
    COMMAND "${_pvpython}" "${_here}/test_python_plugin_parity.py"
      --plugin "${SCHLIEREN_PYTHON_PLUGIN}" --cxx-plugin "${_plugin}" --pvpython "${_pvpython}"
      --example "${PROJECT_SOURCE_DIR}/Examples/first_light.py"
      --work "${_temp}/python_plugin_parity" --reference "${_frontend_ref}"
    PROPERTIES FIXTURES_REQUIRED frontend_reference)
  set_property(TEST python.python_plugin_parity APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
  # issue 47: the Python plugin under MPI (2 ranks of pvbatch, --symmetric): RefractiveIndex's
  # pieces, SchlierenImage traced in pieces, NumericalSchlieren and RefractionOctree against one
  # process (the plugin's algorithms as one piece) and the C++ plugin's compiled filters bit for
  # bit; a failure on rank 1 only agreed on both ranks (test_mpi_python_plugin.py)
  if(MPIEXEC_EXECUTABLE AND _pvbatch)
    schlieren_python_test(mpi_python_plugin
      COMMAND "${MPIEXEC_EXECUTABLE}" ${MPIEXEC_NUMPROC_FLAG} 2 --allow-run-as-root --oversubscribe
        "${_pvbatch}" --mpi --symmetric "${_here}/test_mpi_python_plugin.py"
        --plugin "${SCHLIEREN_PYTHON_PLUGIN}"
      TIMEOUT 60
      PROPERTIES PROCESSORS 2)
    set_property(TEST python.mpi_python_plugin APPEND PROPERTY ENVIRONMENT
      "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
    # the collective guard of the Python plugin (_engine._MpiGuard, the C++ plugin's): a reader
    # failing on rank 1, then on rank 0, in front of RefractiveIndex and SchlierenImage: the other
    # rank fails within SCHLIEREN_MPI_TIMEOUT=5 naming it; in front of SchlierenImage and
    # NumericalSchlieren both ranks fail at once (agreed); then a good pipeline gives one
    # process's image on rank 0 bit for bit (test_mpi_python_deadline.py, about 16 s; before the
    # guard rank 0 waited in the first collective for ever: the TIMEOUT is what a hang hits)
    schlieren_python_test(mpi_python_deadline
      COMMAND "${MPIEXEC_EXECUTABLE}" ${MPIEXEC_NUMPROC_FLAG} 2 --allow-run-as-root --oversubscribe
        "${_pvbatch}" --mpi --symmetric "${_here}/test_mpi_python_deadline.py"
        --plugin "${SCHLIEREN_PYTHON_PLUGIN}" --tmp "${_temp}"
      TIMEOUT 60
      PROPERTIES PROCESSORS 2)
    set_property(TEST python.mpi_python_deadline APPEND PROPERTY ENVIRONMENT
      "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>" "SCHLIEREN_MPI_TIMEOUT=5")
  endif()
  # every value of every property's domain through both plugins in one pvpython: both accept or
  # both refuse naming the property; the properties' documentation (tooltips) and the proxies'
  # help the same (test_frontend_values.py)
  schlieren_python_test(frontend_values
    COMMAND "${_pvpython}" "${_here}/test_frontend_values.py" --cxx-plugin "${_plugin}"
      --python-plugin "${SCHLIEREN_PYTHON_PLUGIN}" --xml "${PROJECT_SOURCE_DIR}/Plugin/Schlieren.xml"
      --work "${_temp}/frontend_values")
  set_property(TEST python.frontend_values APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
  # BodyFromGrid's body beside a mesh's walls (from its velocity) through both plugins: the same
  # solid, n - 1, gradient and note (test_index_walls.py)
  schlieren_python_test(index_walls
    COMMAND "${_pvpython}" "${_here}/test_index_walls.py" --plugin "${SCHLIEREN_PYTHON_PLUGIN}")
  set_property(TEST python.index_walls APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_ENGINE_LIBRARY=$<TARGET_FILE:schlieren_engine>")
endif()

# the Python plugin loaded in the GUI through Tools > Manage Plugins > Load New with X events
# (xdotool under Xvfb and openbox), then Quick Launch, Apply: the image and field data against the
# C++ plugin's references, the proxies' property lists against the C++ plugin's
if(SCHLIEREN_PYTHON_PLUGIN AND SCHLIEREN_XVFB AND _paraview AND SCHLIEREN_XDOTOOL AND SCHLIEREN_OPENBOX
    AND SCHLIEREN_IMPORT)
  schlieren_python_test(gui_python_plugin
    COMMAND "${_with_xvfb}" "${_python}" "${_here}/test_gui_python_plugin.py" --paraview "${_paraview}"
      --pvpython "${_pvpython}" --plugin "${_temp}/gui_python_plugin-no-plugins/none"
      --python-plugin "${SCHLIEREN_PYTHON_PLUGIN}" --cxx-plugin "${_plugin}"
      --reference "${_frontend_ref}" --work "${_temp}/gui_python_plugin"
    TIMEOUT 300
    PROPERTIES FIXTURES_REQUIRED frontend_reference RUN_SERIAL ON)
  set_property(TEST python.gui_python_plugin APPEND PROPERTY ENVIRONMENT
    "SCHLIEREN_XVFB_WM=${SCHLIEREN_OPENBOX}")
endif()
