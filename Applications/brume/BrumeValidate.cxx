// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeCommands.h"

#include "vtkSMPTools.h"

#include "brume/Slab.h"

#include <cstdio>
#include <iostream>
#include <vector>

int RunValidateSlab(const SlabOptions& options)
{
  brume::SlabSpec spec;
  spec.Albedo = options.Albedo;
  spec.OpticalThickness = options.OpticalThickness;
  spec.G = options.G;
  const brume::SlabExperiment experiment(spec, options.Seed);
  if (!experiment.GetError().empty())
  {
    std::cerr << "brume: invalid slab: " << experiment.GetError() << "\n";
    return 1;
  }
  // Fixed blocks merged in order: the same figures for any thread count.
  constexpr std::uint64_t Block = 4096;
  const auto count = static_cast<std::uint64_t>(options.Particles);
  const std::uint64_t blocks = (count + Block - 1) / Block;
  std::vector<brume::SlabTally> tallies(blocks);
  vtkSMPTools::For(0, static_cast<vtkIdType>(blocks),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType b = begin; b < end; ++b)
      {
        const std::uint64_t first = static_cast<std::uint64_t>(b) * Block;
        experiment.Trace(first, std::min(first + Block, count), count, tallies[b]);
      }
    });
  brume::SlabTally total;
  for (const auto& t : tallies)
  {
    total.Add(t);
  }
  std::printf(
    "R_diffuse,R_diffuse_stderr,T_diffuse,T_diffuse_stderr,T_unscattered,T_unscattered_stderr\n");
  std::printf("%.9g,%.3g,%.9g,%.3g,%.9g,%.3g\n", total.Mean(0), total.StandardError(0),
    total.Mean(1), total.StandardError(1), total.Mean(2), total.StandardError(2));
  return 0;
}
