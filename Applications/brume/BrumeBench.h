// SPDX-License-Identifier: BSD-3-Clause
// `brume bench`'s parts: the report of figures with their targets, and the
// benches of each phase (BrumeBench.cxx tracing, BrumeBenchPhases.cxx
// reconstruction and rendering, BrumeBenchCommands.cxx whole commands).
#ifndef BrumeBench_h
#define BrumeBench_h

#include "BrumeCommands.h"

#include "vtkType.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;

namespace BrumeBench
{
inline double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One measured figure, with the target it is held to (issue tracker's
/// figures) or the limit it is compared with.
struct Figure
{
  std::string Key;
  double Value;
  std::string Unit;
  std::string Target; // "<= 0.30", ">= 0.4" or empty
  std::string Note;
};

class Report
{
public:
  /// The targets hold for the default budget only.
  explicit Report(bool targetsApply)
    : TargetsApply(targetsApply)
  {
  }
  void Add(
    std::string key, double value, std::string unit, std::string target = {}, std::string note = {})
  {
    this->Figures.push_back(
      { std::move(key), value, std::move(unit), std::move(target), std::move(note) });
  }
  // Met, missed, or "" without a target (or at another budget).
  const char* Verdict(const Figure& f) const
  {
    if (!this->TargetsApply || f.Target.size() < 4)
    {
      return "";
    }
    const double bound = std::stod(f.Target.substr(3));
    const bool met = f.Target[0] == '<' ? f.Value <= bound : f.Value >= bound;
    return met ? "met" : "missed";
  }
  void PrintSummary() const
  {
    std::printf("\n%-33s %12s %-10s %-10s %s\n", "figure", "value", "unit", "target",
      this->TargetsApply ? "" : "(targets hold at the default particle count)");
    for (const Figure& f : this->Figures)
    {
      std::printf("%-33s %12.4g %-10s %-10s %s\n", f.Key.c_str(), f.Value, f.Unit.c_str(),
        f.Target.c_str(), Verdict(f));
    }
  }
  // The figures as JSON; false (and a message) when the file cannot be written.
  bool WriteJson(const std::string& path, const nlohmann::json& run) const
  {
    nlohmann::json doc = run;
    doc["figures"] = nlohmann::json::array();
    for (const Figure& f : this->Figures)
    {
      nlohmann::json row = { { "key", f.Key }, { "value", f.Value }, { "unit", f.Unit } };
      if (!f.Target.empty())
      {
        row["target"] = f.Target;
      }
      if (*this->Verdict(f))
      {
        row["met"] = std::string(this->Verdict(f)) == "met";
      }
      if (!f.Note.empty())
      {
        row["note"] = f.Note;
      }
      doc["figures"].push_back(row);
    }
    std::ofstream out(path);
    out << doc.dump(2) << '\n';
    out.close();
    if (!out)
    {
      std::fprintf(stderr, "brume bench: cannot write %s\n", path.c_str());
      return false;
    }
    return true;
  }

private:
  bool TargetsApply;
  std::vector<Figure> Figures;
};

/// Phase 2: the full reconstruction and a view update (best of 3); returns
/// the view update's seconds.
double BenchReconstruction(vtkAlgorithm* source, vtkAlgorithm* tracer, Report& report);

/// Phase 3: frames of the default scene, and of its medium alone with the
/// slice mapper and with vtkGPUVolumeRayCastMapper on the same volume.
void BenchRendering(vtkAlgorithm* source, vtkAlgorithm* tracer, double update, Report& report);

/// A VTK program's renderer lit through vtkBrumePass at `particles`.
void BenchPass(long long particles, int volumePoints, Report& report);

/// A mirror at display time (the default scene with its floor a mirror).
void BenchMirror(
  vtkDataObject* defaultScene, vtkIdType particles, std::uint64_t seed, Report& report);

/// `brume render` and `brume view` as whole processes (medians of 3);
/// false, after saying so, when a command fails.
bool BenchWholeCommands(const BenchOptions& options, Report& report);
}

#endif
