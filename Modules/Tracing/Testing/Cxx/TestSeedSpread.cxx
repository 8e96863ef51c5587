// SPDX-License-Identifier: BSD-3-Clause
// Particles are independent: the slab estimates of many seeds scatter as
// much as the standard errors each run reports, no more and no less.
//
// usage: TestSeedSpread PARTICLES SEEDS SPEC...
//        TestSeedSpread PARTICLES SEEDS --table CSV
//   SPEC: albedo,optical_thickness,g (for example 0.99,16,0.99)
//   CSV:  the adding-doubling table (../shared/reference/slab_collimated.csv);
//         skipped (exit 125) when absent.
//
// For every slab and quantity, the runs with seeds 1..SEEDS give estimates
// m_i with standard errors s_i. If particles are independent and s_i is
// true, X = sum_i ((m_i - m)/s_i)^2 about the inverse-variance-weighted mean
// m follows a chi-square law with SEEDS - 1 degrees of freedom. Correlated
// particles make the spread exceed the reported errors and X large; an
// overstated error makes X small. The test fails when X lies in either tail
// beyond a family-wise probability of 1e-3 (Bonferroni over every slab and
// quantity tested). The chi-square tail comes from the Wilson-Hilferty cube
// root transform, accurate to a few per cent of the probability here.
//
// Quantities with fewer than 100 expected events per run (where the normal
// law of the estimate does not hold yet) are reported and not tested.
#include "vtkBrumeSMP.h"

#include "brume/Slab.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct Spread
{
  double Statistic = 0.0;
  double Mean = 0.0;
  double StandardDeviation = 0.0;
  double MeanError = 0.0;
};

Spread Measure(const std::vector<double>& m, const std::vector<double>& s)
{
  Spread r;
  double weights = 0.0, weighted = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i)
  {
    const double w = 1.0 / (s[i] * s[i]);
    weights += w;
    weighted += w * m[i];
    sum += m[i];
    r.MeanError += s[i];
  }
  const double n = static_cast<double>(m.size());
  const double center = weighted / weights;
  r.Mean = sum / n;
  r.MeanError /= n;
  for (std::size_t i = 0; i < m.size(); ++i)
  {
    const double z = (m[i] - center) / s[i];
    r.Statistic += z * z;
    r.StandardDeviation += (m[i] - r.Mean) * (m[i] - r.Mean);
  }
  r.StandardDeviation = std::sqrt(r.StandardDeviation / (n - 1.0));
  return r;
}

/// P(chi-square with k degrees of freedom > x), Wilson-Hilferty.
double UpperTail(double x, double k)
{
  const double v = 2.0 / (9.0 * k);
  const double z = (std::cbrt(x / k) - (1.0 - v)) / std::sqrt(v);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

bool ParseSpec(const std::string& text, brume::SlabSpec& spec)
{
  std::stringstream fields(text);
  std::string f;
  std::vector<double> v;
  while (v.size() < 3 && std::getline(fields, f, ','))
  {
    // Tolerate surrounding spaces and a CRLF line ending.
    while (!f.empty() && std::isspace(static_cast<unsigned char>(f.back())))
    {
      f.pop_back();
    }
    char* end = nullptr;
    v.push_back(std::strtod(f.c_str(), &end));
    if (end == f.c_str() || *end != '\0')
    {
      return false;
    }
  }
  if (v.size() < 3)
  {
    return false;
  }
  spec.Albedo = v[0];
  spec.OpticalThickness = v[1];
  spec.G = v[2];
  return true;
}
}

int TestSeedSpread(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::cerr << "usage: TestSeedSpread PARTICLES SEEDS SPEC... | --table CSV\n";
    return EXIT_FAILURE;
  }
  const auto particles = static_cast<std::uint64_t>(std::atoll(argv[1]));
  const int seeds = std::atoi(argv[2]);
  if (particles < 1000 || seeds < 5)
  {
    std::cerr << "Need at least 1000 particles and 5 seeds.\n";
    return EXIT_FAILURE;
  }

  std::vector<brume::SlabSpec> specs;
  if (std::string(argv[3]) == "--table")
  {
    std::ifstream csv(argc > 4 ? argv[4] : "");
    if (!csv)
    {
      std::cout << "Reference table " << (argc > 4 ? argv[4] : "(none)")
                << " not found: skipped.\n";
      return 125;
    }
    std::string line;
    std::getline(csv, line); // header
    while (std::getline(csv, line))
    {
      brume::SlabSpec spec;
      if (!ParseSpec(line, spec))
      {
        std::cerr << "Malformed row: " << line << "\n";
        return EXIT_FAILURE;
      }
      specs.push_back(spec);
    }
  }
  else
  {
    for (int a = 3; a < argc; ++a)
    {
      brume::SlabSpec spec;
      if (!ParseSpec(argv[a], spec))
      {
        std::cerr << "Malformed slab '" << argv[a] << "': expected albedo,thickness,g\n";
        return EXIT_FAILURE;
      }
      specs.push_back(spec);
    }
  }

  const char* names[3] = { "R_diffuse", "T_diffuse", "T_unscattered" };
  struct Row
  {
    brume::SlabSpec Spec;
    int Quantity;
    Spread S;
    bool Tested;
  };
  std::vector<Row> rows;
  for (const brume::SlabSpec& spec : specs)
  {
    std::vector<double> m[3], s[3];
    for (int seed = 1; seed <= seeds; ++seed)
    {
      const brume::SlabExperiment experiment(spec, static_cast<std::uint64_t>(seed));
      if (!experiment.GetError().empty())
      {
        std::cerr << experiment.GetError() << "\n";
        return EXIT_FAILURE;
      }
      const brume::SlabTally tally = experiment.Run(particles, vtkBrumeSMP::ParallelFor());
      for (int q = 0; q < 3; ++q)
      {
        m[q].push_back(tally.Mean(q));
        s[q].push_back(tally.StandardError(q));
      }
    }
    for (int q = 0; q < 3; ++q)
    {
      double lowest = m[q][0], smallestError = s[q][0];
      for (int i = 0; i < seeds; ++i)
      {
        lowest = std::min(lowest, m[q][i]);
        smallestError = std::min(smallestError, s[q][i]);
      }
      // Fewer than ~100 events per run: the estimate is not normal yet.
      const bool tested = smallestError > 0.0 && lowest * static_cast<double>(particles) >= 100.0 &&
        (1.0 - lowest) * static_cast<double>(particles) >= 100.0;
      Row row{ spec, q, Spread{}, tested };
      if (tested)
      {
        row.S = Measure(m[q], s[q]);
      }
      rows.push_back(row);
    }
  }

  int tests = 0;
  for (const Row& row : rows)
  {
    tests += row.Tested ? 1 : 0;
  }
  const double alpha = 1e-3 / (2.0 * std::max(tests, 1));
  const double dof = seeds - 1;
  std::printf("%d seeds x %llu particles; each tail below %.2g fails\n", seeds,
    static_cast<unsigned long long>(particles), alpha);
  std::printf("%-5s %-6s %-5s %-14s %10s %10s %10s %6s %8s %9s\n", "a", "tau", "g", "quantity",
    "mean", "spread", "stderr", "ratio", "chi2", "P(>chi2)");
  bool ok = true;
  for (const Row& row : rows)
  {
    std::printf("%-5g %-6g %-5g %-14s ", row.Spec.Albedo, row.Spec.OpticalThickness, row.Spec.G,
      names[row.Quantity]);
    if (!row.Tested)
    {
      std::printf("(fewer than 100 events per run: not tested)\n");
      continue;
    }
    const Spread& s = row.S;
    const double upper = UpperTail(s.Statistic, dof);
    const bool pass = upper >= alpha && (1.0 - upper) >= alpha;
    ok = ok && pass;
    std::printf("%10.6g %10.3g %10.3g %6.2f %8.1f %9.2g%s\n", s.Mean, s.StandardDeviation,
      s.MeanError, s.StandardDeviation / s.MeanError, s.Statistic, upper, pass ? "" : "  FAIL");
  }
  std::printf("chi-square with %g degrees of freedom: %d quantities tested\n", dof, tests);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
