// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeHistogramReduction
 * @brief   exact histograms summed across the processes of a controller
 *
 * The core's brume::HistogramReduction on a vtkMultiProcessController:
 * every process bins its own hits into fixed-point histograms
 * (brume::ExactHistogram), whose sums do not depend on the order of their
 * terms; one reduction then gives the totals, bitwise those of one
 * process holding every hit, whatever the number of processes and
 * threads: to the process that estimates the object's texture
 * (MPI_Reduce through vtkMultiProcessController, a tree), which then
 * broadcasts the texture (MPI_Bcast), or to every process (MPI_Allreduce).
 * The processes share out the shadow rays of the direct light, which one
 * all-gather (MPI_Allgatherv) gives back to all. It counts the bytes it
 * moves and the seconds it spends (waiting for the slowest process
 * included).
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
  void SumOnto(std::vector<std::int64_t>& values, int root) override;
  void Broadcast(std::vector<float>& data, int root) override;
  void Gather(const std::vector<std::int32_t>& mine, const std::vector<std::size_t>& counts,
    std::vector<std::int32_t>& all) override;

  /// Time spent in the reductions so far.
  double Seconds = 0.0;

private:
  vtkMultiProcessController* Controller;
  std::vector<std::int64_t> Totals; // received sums, kept from one reduction to the next
};

#endif
