// SPDX-License-Identifier: BSD-3-Clause
#ifndef SchlierenPythonPath_h
#define SchlierenPythonPath_h

// The plugin's initializer (paraview_add_plugin INITIALIZERS): puts the folder Schlieren.so was
// loaded from at the front of Python's sys.path (now, or when Python starts), so that
// `import schlieren_view` finds Plugin/schlieren_view.py, which the build and the install place
// beside Schlieren.so. This replaces PYTHON_MODULES, whose meaning changed in ParaView 6.1: there
// the modules are loaded as Python algorithm plugins and the generated GetXMLs() then replaces
// the plugin's server-manager XML with theirs (LoadPlugin succeeds, RefractiveScene is undefined).
void SchlierenPrependPythonPath();

#endif
