// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeHistogramReduction
 * @brief   exact histograms summed across the processes of a controller
 *
 * The core's brume::HistogramReduction on a vtkMultiProcessController:
 * every process bins its own hits into fixed-point histograms
 * (brume::ExactHistogram), whose sums do not depend on the order of their
 * terms; one all-reduce (MPI_Allreduce through vtkMultiProcessController,
 * a tree: about 2 log2 R steps) then gives every process the totals,
 * bitwise those of one process holding every hit, whatever the number of
 * processes and threads. The processes share out the per-texel work of
 * the regions, which one all-gather (MPI_Allgatherv) gives back to all. It
 * counts the bytes it moves and the seconds it spends (waiting for the
 * slowest process included).
 *
 * @sa vtkBrumeProcesses brume::ObjectRadiance::SetReduction
 */
#ifndef vtkBrumeHistogramReduction_h
#define vtkBrumeHistogramReduction_h

#include "vtkBrumeParallelModule.h" // For export macro

#include "brume/Reconstruction.h" // For brume::HistogramReduction

class vtkMultiProcessController;

class VTKBRUMEPARALLEL_EXPORT vtkBrumeHistogramReduction : public brume::HistogramReduction
{
public:
  explicit vtkBrumeHistogramReduction(vtkMultiProcessController* controller);

  int NumberOfProcesses() const override;
  int Rank() const override;
  std::int64_t Max(std::int64_t value) override;
  void Sum(std::vector<std::int64_t>& values) override;
  void Gather(const std::vector<std::int32_t>& mine, const std::vector<std::size_t>& counts,
    std::vector<std::int32_t>& all) override;

  /// Time spent in the reductions so far.
  double Seconds = 0.0;

private:
  vtkMultiProcessController* Controller;
};

#endif
