// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeCommands.h"

#include "vtkBrumeSMP.h"

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
  const brume::SlabTally total =
    experiment.Run(static_cast<std::uint64_t>(options.Particles), vtkBrumeSMP::ParallelFor());
  std::printf(
    "R_diffuse,R_diffuse_stderr,T_diffuse,T_diffuse_stderr,T_unscattered,T_unscattered_stderr\n");
  std::printf("%.9g,%.3g,%.9g,%.3g,%.9g,%.3g\n", total.Mean(0), total.StandardError(0),
    total.Mean(1), total.StandardError(1), total.Mean(2), total.StandardError(2));
  return 0;
}
