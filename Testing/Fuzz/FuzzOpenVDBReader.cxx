// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: any bytes as a .vdb file, read with a 64 MiB cap on the
// dense copy. The reader must fail cleanly or succeed.
#include "vtkBrumeOpenVDBReader.h"
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
  const std::string file = "fuzz-volume-" + std::to_string(::getpid()) + ".vdb";
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  vtkNew<vtkBrumeOpenVDBReader> reader;
  reader->SetFileName(file.c_str());
  reader->SetMemoryLimit(64 << 20);
  reader->GetExecutive()->Update();
  return 0;
}
