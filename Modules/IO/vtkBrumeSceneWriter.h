// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSceneWriter
 * @brief   saves a scene collection as a Brume scene file (versioned JSON)
 *
 * The JSON names one .vtp file per surface (with its point, cell and field
 * arrays) and one .vti file per medium that carries a density array, written
 * beside it as `<stem>-<object>.vtp|.vti`; homogeneous and OpenVDB media,
 * lights, camera and render settings are written inline. vtkBrumeSceneReader
 * reads it back into the same scene.
 *
 * @sa vtkBrumeSceneReader
 */
#ifndef vtkBrumeSceneWriter_h
#define vtkBrumeSceneWriter_h

#include "vtkBrumeIOModule.h" // For export macro
#include "vtkWriter.h"

#include <string> // For FileName

class VTKBRUMEIO_EXPORT vtkBrumeSceneWriter : public vtkWriter
{
public:
  static vtkBrumeSceneWriter* New();
  vtkTypeMacro(vtkBrumeSceneWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The scene file (.json).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

protected:
  vtkBrumeSceneWriter() = default;
  ~vtkBrumeSceneWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;

private:
  vtkBrumeSceneWriter(const vtkBrumeSceneWriter&) = delete;
  void operator=(const vtkBrumeSceneWriter&) = delete;
};

#endif
