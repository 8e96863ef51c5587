// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeHistogramChain
 * @brief   histograms summed along the processes of a controller, in rank order
 *
 * The core's brume::HistogramChain on a vtkMultiProcessController: process
 * r receives the running sums of processes 0..r-1, adds its own hits, and
 * sends the sums to process r + 1; the last process broadcasts the totals.
 * The sums are then bitwise those of one process holding every hit. It
 * counts the bytes it moves and the seconds it spends (waiting for the
 * processes before it included).
 *
 * @sa vtkBrumeProcesses brume::ObjectRadiance::SetChain
 */
#ifndef vtkBrumeHistogramChain_h
#define vtkBrumeHistogramChain_h

#include "vtkBrumeParallelModule.h" // For export macro

#include "brume/Reconstruction.h" // For brume::HistogramChain

class vtkMultiProcessController;

class VTKBRUMEPARALLEL_EXPORT vtkBrumeHistogramChain : public brume::HistogramChain
{
public:
  explicit vtkBrumeHistogramChain(vtkMultiProcessController* controller);

  void Receive(std::vector<double>& values) override;
  void Forward(std::vector<double>& values) override;

  /// Time spent in the chain so far.
  double Seconds = 0.0;

private:
  vtkMultiProcessController* Controller;
};

#endif
