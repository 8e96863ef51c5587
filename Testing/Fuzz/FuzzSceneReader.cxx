// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: any bytes as a scene file. The reader must fail cleanly or
// succeed; sanitizers report anything else. Relative file names in the input
// resolve inside the fuzzing directory (the BadScenes support files are copied
// there by scripts/fuzz.sh).
#include "vtkBrumeSceneReader.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  vtkObject::GlobalWarningDisplayOff();
  const std::string file = "fuzz-scene-" + std::to_string(::getpid()) + ".json";
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  vtkNew<vtkBrumeSceneReader> reader;
  reader->SetFileName(file.c_str());
  reader->GetExecutive()->Update();
  return 0;
}
