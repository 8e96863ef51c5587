// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeLightTracer.h"

#include "vtkBrumeSceneConversion.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include "brume/LightTracer.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkBrumeLightTracer);

namespace
{
// Particles per block: blocks, not threads, own the output order.
constexpr vtkTypeInt64 ParticlesPerBlock = 4096;

struct TraceBlocks
{
  const brume::LightTracer& Tracer;
  std::vector<std::vector<brume::Hit>>& Hits;
  std::vector<brume::TraceCounters>& Counters;
  vtkTypeInt64 Particles;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    for (vtkIdType b = begin; b < end; ++b)
    {
      const vtkTypeInt64 first = b * ParticlesPerBlock;
      const vtkTypeInt64 last = std::min(first + ParticlesPerBlock, this->Particles);
      std::vector<brume::Hit>& hits = this->Hits[b];
      hits.reserve(static_cast<std::size_t>(4 * (last - first)));
      for (vtkTypeInt64 i = first; i < last; ++i)
      {
        this->Tracer.TraceParticle(static_cast<std::uint64_t>(i),
          static_cast<std::uint64_t>(this->Particles), hits, this->Counters[b]);
      }
    }
  }
};
}

vtkBrumeLightTracer::vtkBrumeLightTracer()
{
  this->SetNumberOfInputPorts(1);
}

int vtkBrumeLightTracer::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPartitionedDataSetCollection");
  return 1;
}

int vtkBrumeLightTracer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto* input = vtkPartitionedDataSetCollection::GetData(inputVector[0], 0);
  auto* output = vtkPolyData::GetData(outputVector, 0);
  this->LastRayCount = 0;

  const vtkTypeInt64 particles = this->NumberOfParticles;
  if (particles < 1 || particles > vtkTypeInt64(10000000000LL))
  {
    vtkErrorMacro("NumberOfParticles must be in [1, 1e10], not " << particles << ".");
    return 0;
  }
  // A particle stores one hit per interaction; a few per particle is typical.
  const double expectedBytes = 4.0 * static_cast<double>(particles) * sizeof(brume::Hit);
  if (expectedBytes > static_cast<double>(this->MemoryLimit))
  {
    vtkErrorMacro("" << particles << " particles would need about " << expectedBytes / (1 << 20)
                     << " MiB of hits, more than MemoryLimit (" << this->MemoryLimit / (1 << 20)
                     << " MiB).");
    return 0;
  }

  brume::Scene scene;
  const std::string error = vtkBrumeSceneConversion::ToScene(input, scene);
  if (!error.empty())
  {
    vtkErrorMacro("Invalid scene: " << error << ".");
    return 0;
  }
  const brume::RayCaster caster(scene);
  if (!caster.GetError().empty())
  {
    vtkErrorMacro("Could not build the ray-casting structure: " << caster.GetError());
    return 0;
  }
  brume::TraceSettings settings;
  settings.Seed = this->Seed;
  settings.MaxDepth = this->MaximumDepth;
  settings.RouletteDepth = this->RouletteDepth;
  const brume::LightTracer tracer(scene, caster, settings);

  const vtkTypeInt64 blocks = (particles + ParticlesPerBlock - 1) / ParticlesPerBlock;
  std::vector<std::vector<brume::Hit>> blockHits(static_cast<std::size_t>(blocks));
  std::vector<brume::TraceCounters> counters(static_cast<std::size_t>(blocks));
  TraceBlocks functor{ tracer, blockHits, counters, particles };
  // Trace in a few batches so that progress reaches the user from this thread.
  const vtkTypeInt64 batches = std::min<vtkTypeInt64>(blocks, 20);
  for (vtkTypeInt64 k = 0; k < batches && !this->GetAbortExecute(); ++k)
  {
    const vtkTypeInt64 begin = blocks * k / batches, end = blocks * (k + 1) / batches;
    vtkSMPTools::For(begin, end, functor);
    this->UpdateProgress(0.95 * static_cast<double>(k + 1) / static_cast<double>(batches));
  }

  std::size_t total = 0;
  brume::TraceCounters sum;
  for (std::size_t b = 0; b < blockHits.size(); ++b)
  {
    total += blockHits[b].size();
    sum.Add(counters[b]);
  }
  std::vector<brume::Hit> hits;
  hits.reserve(total);
  for (auto& block : blockHits)
  {
    hits.insert(hits.end(), block.begin(), block.end());
    std::vector<brume::Hit>().swap(block);
  }
  this->LastRayCount = static_cast<vtkTypeInt64>(sum.Rays);
  output->ShallowCopy(
    vtkBrumeSceneConversion::HitsToPolyData(hits, tracer.GetTotalPower(), particles));
  this->UpdateProgress(1.0);
  return 1;
}

void vtkBrumeLightTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumDepth: " << this->MaximumDepth << "\n";
  os << indent << "RouletteDepth: " << this->RouletteDepth << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
}
