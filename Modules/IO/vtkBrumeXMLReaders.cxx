// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeXMLReaders.h"

#include "vtkObjectFactory.h"
#include "vtk_expat.h"

#include <dlfcn.h>

vtkStandardNewMacro(vtkBrumeXMLDataParser);

namespace
{
using SetReparseDeferral = XML_Bool (*)(XML_Parser, XML_Bool);

// Looked up at run time, not linked: Brume built against an expat that
// declares it still runs with one that lacks it, and the other way round.
// It is looked up in the expat that VTK's parser calls (the library holding
// XML_ParserCreate()), not in the process's global scope, which does not
// hold it where Python or ParaView loaded Brume (RTLD_LOCAL).
SetReparseDeferral ReparseDeferralSetter()
{
  static const SetReparseDeferral setter = []() -> SetReparseDeferral
  {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&XML_ParserCreate), &info) || !info.dli_fname)
    {
      return nullptr;
    }
    // Already loaded (VTK's parser links it): this only takes a reference.
    void* expat = dlopen(info.dli_fname, RTLD_LAZY | RTLD_NOLOAD);
    return expat
      ? reinterpret_cast<SetReparseDeferral>(dlsym(expat, "XML_SetReparseDeferralEnabled"))
      : nullptr;
  }();
  return setter;
}
}

int vtkBrumeXMLDataParser::CreateParser()
{
  if (!this->Superclass::CreateParser())
  {
    return 0;
  }
  if (const SetReparseDeferral setter = ReparseDeferralSetter())
  {
    setter(static_cast<XML_Parser>(this->Parser), XML_FALSE);
  }
  return 1;
}
