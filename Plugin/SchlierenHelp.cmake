# The plugin's help pages where ParaView's paraview_add_plugin leaves them out (5.12 and 5.13
# built with Qt 6; Plugin/CMakeLists.txt decides). The same steps as ParaView's macro takes on
# Qt 5, with ParaView's own CMake functions and XSL: the proxies' HTML from Schlieren.xml by Qt 5's
# xmlpatterns (Debian 13: qtxmlpatterns5-dev-tools; only the command-line tool, nothing of Qt 5 is
# linked), the .qch by Qt 6's qhelpgenerator (namespace Schlieren.org, folder Schlieren, as on
# 5.11), base64-encoded into Schlieren_qch.h by ParaView's ProcessXML; SchlierenHelp.cxx writes it
# to a temporary file and registers it with the GUI's help engine when the toolbar is made.
# Sets _schlieren_help_sources; without xmlpatterns, a warning and no help pages (as before).
set(_schlieren_help_sources)
find_program(qt_xmlpatterns_executable
  NAMES xmlpatterns-qt5 xmlpatterns
  HINTS /usr/lib/qt5/bin "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/qt5/bin"
  DOC "Path to Qt 5's xmlpatterns (the plugin's help pages on ParaView 5.12/5.13 with Qt 6)")
set(_schlieren_xmlpatterns_ok FALSE)
if(qt_xmlpatterns_executable)
  # /usr/bin/xmlpatterns can be qtchooser's link with no Qt 5 xmlpatterns behind it
  execute_process(COMMAND "${qt_xmlpatterns_executable}" -help
    RESULT_VARIABLE _schlieren_xmlpatterns_rc OUTPUT_VARIABLE _schlieren_xmlpatterns_out
    ERROR_VARIABLE _schlieren_xmlpatterns_out)
  if(_schlieren_xmlpatterns_rc EQUAL 0 AND _schlieren_xmlpatterns_out MATCHES "xmlpatterns")
    set(_schlieren_xmlpatterns_ok TRUE)
  endif()
endif()
if(NOT _schlieren_xmlpatterns_ok)
  message(WARNING "ParaView ${ParaView_VERSION} with Qt ${PARAVIEW_QT_MAJOR_VERSION}: the plugin's help "
    "pages need Qt 5's xmlpatterns (Debian: apt-get install qtxmlpatterns5-dev-tools); building without them")
  set(SCHLIEREN_OWN_HELP OFF)
  return()
endif()
find_package(Qt${PARAVIEW_QT_MAJOR_VERSION} REQUIRED COMPONENTS Help)
set(_schlieren_help_dir "${CMAKE_CURRENT_BINARY_DIR}/paraview_help")
paraview_client_documentation(
  TARGET     Schlieren_doc
  OUTPUT_DIR "${_schlieren_help_dir}"
  XMLS       "${CMAKE_CURRENT_SOURCE_DIR}/Schlieren.xml")
paraview_client_generate_help(
  NAME        Schlieren
  OUTPUT_PATH _schlieren_qch
  OUTPUT_DIR  "${_schlieren_help_dir}"
  TARGET      Schlieren_qch
  DEPENDS     Schlieren_doc
  PATTERNS    "*.html" "*.css" "*.png" "*.jpg" "*.js")
set(_schlieren_qch_header "${CMAKE_CURRENT_BINARY_DIR}/Schlieren_qch.h")
add_custom_command(
  OUTPUT "${_schlieren_qch_header}"
  # (the empty argument quoted for the shell, as ParaView's macro does)
  COMMAND "$<TARGET_FILE:ParaView::ProcessXML>" -base64 "${_schlieren_qch_header}" \"\" "_qch" "_qch"
    "${_schlieren_qch}"
  DEPENDS "${_schlieren_qch}" Schlieren_qch "$<TARGET_FILE:ParaView::ProcessXML>"
  COMMENT "Embedding the Schlieren help (.qch)")
set_property(SOURCE "${_schlieren_qch_header}" PROPERTY SKIP_AUTOMOC ON)
set(_schlieren_help_sources SchlierenHelp.cxx SchlierenHelp.h "${_schlieren_qch_header}")
