// SPDX-License-Identifier: BSD-3-Clause
// A radiance image written by `brume render -o FILE.vti` reads back with
// VTK's own reader: the expected size, a finite float RGB `Radiance` array.
// (Appended XML data does not read back where expat defers reparsing, as
// Debian 12's does; Brume writes inline binary.)
#include "vtkBrumeDataModelNames.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataReader.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

int TestReadRadiance(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::cerr << "usage: TestReadRadiance FILE.vti WIDTH HEIGHT\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  int dims[3];
  reader->GetOutput()->GetDimensions(dims);
  auto* radiance = vtkFloatArray::SafeDownCast(
    reader->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Radiance));
  if (dims[0] != std::atoi(argv[2]) || dims[1] != std::atoi(argv[3]) || !radiance ||
    radiance->GetNumberOfComponents() != 3)
  {
    std::cerr << argv[1] << ": read " << dims[0] << " x " << dims[1] << " pixels"
              << (radiance ? "" : " without a float 'Radiance' array") << "\n";
    return EXIT_FAILURE;
  }
  double sum = 0.0;
  for (vtkIdType i = 0; i < radiance->GetNumberOfValues(); ++i)
  {
    if (!std::isfinite(radiance->GetValue(i)))
    {
      std::cerr << argv[1] << ": non-finite radiance at value " << i << "\n";
      return EXIT_FAILURE;
    }
    sum += radiance->GetValue(i);
  }
  std::cout << argv[1] << ": " << dims[0] << " x " << dims[1] << ", mean radiance "
            << sum / radiance->GetNumberOfValues() << "\n";
  return sum > 0.0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
