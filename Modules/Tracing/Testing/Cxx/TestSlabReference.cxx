// SPDX-License-Identifier: BSD-3-Clause
// Phase 1 against published adding-doubling values for a slab lit by a
// collimated beam (../shared/reference/slab_collimated.csv).
//
// usage: TestSlabReference CSV PARTICLES [ROWS]
//   ROWS: comma-separated 1-based row numbers (default: every row).
// Every quantity must agree within 4 of its Monte Carlo standard errors and
// within 0.002 absolute. Skips (exit 125) when the table is absent, as in a
// user's clone without ../shared.
#include "vtkBrumeSMP.h"

#include "brume/Slab.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{
brume::SlabTally Run(const brume::SlabSpec& spec, std::uint64_t particles)
{
  const brume::SlabExperiment experiment(spec, 1);
  return experiment.Run(particles, vtkBrumeSMP::ParallelFor());
}
}

int TestSlabReference(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestSlabReference CSV PARTICLES [ROWS]\n";
    return EXIT_FAILURE;
  }
  std::ifstream csv(argv[1]);
  if (!csv)
  {
    std::cout << "Reference table " << argv[1] << " not found: skipped.\n";
    return 125;
  }
  const auto particles = static_cast<std::uint64_t>(std::atoll(argv[2]));
  std::set<int> rows;
  if (argc > 3)
  {
    std::stringstream list(argv[3]);
    std::string item;
    while (std::getline(list, item, ','))
    {
      rows.insert(std::atoi(item.c_str()));
    }
  }
  std::string line;
  std::getline(csv, line); // header
  const char* names[3] = { "R_diffuse", "T_diffuse", "T_unscattered" };
  std::printf("%-5s %-6s %-5s %-14s %12s %12s %10s %7s\n", "a", "tau", "g", "quantity", "reference",
    "brume", "stderr", "z");
  bool ok = true;
  double worst = 0.0;
  for (int row = 1; std::getline(csv, line); ++row)
  {
    if (!rows.empty() && !rows.count(row))
    {
      continue;
    }
    std::stringstream fields(line);
    std::vector<double> v;
    std::string f;
    while (std::getline(fields, f, ','))
    {
      v.push_back(std::atof(f.c_str()));
    }
    if (v.size() < 6)
    {
      std::cerr << "Malformed row " << row << ": " << line << "\n";
      return EXIT_FAILURE;
    }
    brume::SlabSpec spec;
    spec.Albedo = v[0];
    spec.OpticalThickness = v[1];
    spec.G = v[2];
    const brume::SlabTally tally = Run(spec, particles);
    for (int q = 0; q < 3; ++q)
    {
      const double reference = v[3 + q], mean = tally.Mean(q), se = tally.StandardError(q);
      const double delta = mean - reference;
      double z = 0.0;
      bool pass = std::abs(delta) <= 0.002;
      if (se > 0.0)
      {
        z = delta / se;
        pass = pass && std::abs(z) <= 4.0;
      }
      else
      {
        // No event seen: plausible only if fewer than about 3 were expected.
        pass = pass && reference * static_cast<double>(particles) < 3.0;
      }
      worst = std::max(worst, std::abs(z));
      std::printf("%-5g %-6g %-5g %-14s %12.6g %12.6g %10.3g %7.2f%s\n", spec.Albedo,
        spec.OpticalThickness, spec.G, names[q], reference, mean, se, z, pass ? "" : "  FAIL");
      ok = ok && pass;
    }
  }
  std::printf("largest |z| = %.2f with %llu particles per row\n", worst,
    static_cast<unsigned long long>(particles));
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
