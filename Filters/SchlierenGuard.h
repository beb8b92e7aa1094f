// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenGuard.h
 * @brief Internal to the filters: no exception leaves a pipeline request.
 *
 * A request that throws (std::bad_alloc from an allocation the machine cannot give, an engine
 * error not caught on the way) would otherwise unwind through VTK's executive and abort ParaView.
 * Each filter's ProcessRequest runs the superclass's inside SchlierenGuarded: an exception becomes
 * an error message, empty outputs and a failed request (0).
 */
#ifndef SchlierenGuard_h
#define SchlierenGuard_h

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkSetGet.h"

#include <exception>
#include <new>

template <typename Request>
int SchlierenGuarded(vtkAlgorithm* self, Request&& request)
{
  try
  {
    return request();
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorWithObjectMacro(self, "Out of memory: an allocation this filter needed failed "
                                  "(std::bad_alloc). Lower the sizes its properties set "
                                  "(Dimensions, SamplingDimensions or AutomaticDimension, "
                                  "Resolution), or free memory.");
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << e.what());
  }
  for (int port = 0; port < self->GetNumberOfOutputPorts(); ++port)
  {
    if (vtkDataObject* out = self->GetOutputDataObject(port))
    {
      out->Initialize();
    }
  }
  return 0;
}

#endif
