// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenPythonPath.h"

#include "vtkPythonInterpreter.h"

#include <string>

#if !defined(_WIN32)
#include <dlfcn.h>
#endif

void SchlierenPrependPythonPath()
{
#if !defined(_WIN32)
  // the file this function is in: Schlieren.so, wherever ParaView loaded it from
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&SchlierenPrependPythonPath), &info) == 0 || !info.dli_fname)
  {
    return;
  }
  const std::string path(info.dli_fname);
  const std::string::size_type slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return;
  }
  // saved by VTK and applied when Python is initialized, if it is not yet
  vtkPythonInterpreter::PrependPythonPath(path.substr(0, slash).c_str());
#endif
}
