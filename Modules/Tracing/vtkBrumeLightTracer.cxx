// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeLightTracerOutput.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeHitConversion.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "brume/LightTracer.h"

#include <algorithm>
#include <cstdlib>
#include <new>
#include <vector>

vtkStandardNewMacro(vtkBrumeLightTracer);

double vtkBrumeLightTracer::ExpectedHitBytes(vtkTypeInt64 particles)
{
  // A particle stores one hit per interaction; a few per particle is typical.
  return 4.0 * static_cast<double>(particles) * sizeof(brume::Hit);
}

namespace
{
// Particles per block: blocks, not threads, own the output order.
constexpr auto ParticlesPerBlock = static_cast<vtkTypeInt64>(brume::LightTracer::ParticlesPerBlock);

struct TraceBlocks
{
  const brume::LightTracer& Tracer;
  std::vector<std::vector<brume::Hit>>& Hits;
  std::vector<brume::TraceCounters>& Counters;
  vtkTypeInt64 Particles; // the run's count (normalization)
  vtkTypeInt64 FirstParticle;
  vtkTypeInt64 EndParticle; // this execution traces [FirstParticle, EndParticle)
  vtkTypeInt64 FirstBlock;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    for (vtkIdType b = begin; b < end; ++b)
    {
      const vtkTypeInt64 first = this->FirstParticle + (this->FirstBlock + b) * ParticlesPerBlock;
      const vtkTypeInt64 last = std::min(first + ParticlesPerBlock, this->EndParticle);
      // The block's hit vector and counters are worked on here, not in
      // place: neighbouring blocks' vector headers and counters share cache
      // lines, and threads updating them per hit would contend for the lines
      // (2 threads: 35 % of the tracing time when blocks interleave).
      std::vector<brume::Hit> hits;
      hits.swap(this->Hits[b]); // its buffer, reused from batch to batch
      hits.clear();
      hits.reserve(static_cast<std::size_t>(4 * (last - first)));
      brume::TraceCounters counters;
      this->Tracer.TraceParticles(static_cast<std::uint64_t>(first),
        static_cast<std::uint64_t>(last), static_cast<std::uint64_t>(this->Particles), hits,
        counters);
      this->Hits[b].swap(hits);
      this->Counters[b] = counters;
    }
  }
};

template <typename T>
void AddTuple(vtkPolyData* output, const char* name, const T& v)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->InsertNextTuple3(v[0], v[1], v[2]);
  output->GetFieldData()->AddArray(a);
}
}

struct vtkBrumeLightTracer::BatchMemory
{
  std::vector<std::vector<brume::Hit>> BlockHits;
};

vtkBrumeLightTracer::vtkBrumeLightTracer()
  : Lights(vtkSmartPointer<vtkLightCollection>::New())
  , Returned(new vtkBrumeLightTracerReturnedBuffers)
{
  this->SetNumberOfInputPorts(1);
}

// The output's arrays may outlive the tracer: they free their buffers then.
vtkBrumeLightTracer::~vtkBrumeLightTracer() = default;

void vtkBrumeLightTracer::AddLight(vtkLight* light)
{
  this->Lights->AddItem(light);
  this->Modified();
}

void vtkBrumeLightTracer::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

vtkLightCollection* vtkBrumeLightTracer::GetLights()
{
  return this->Lights;
}

vtkMTimeType vtkBrumeLightTracer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  this->Lights->InitTraversal();
  while (vtkLight* light = this->Lights->GetNextItem())
  {
    t = std::max(t, light->GetMTime());
  }
  return t;
}

int vtkBrumeLightTracer::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Any number of pieces: each traces its share of the particles.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkBrumeLightTracer::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

vtkTypeBool vtkBrumeLightTracer::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The executive asks which outputs will not be generated just before it
  // lets go of the output's data (PrepareForNewData) and executes: the
  // output lets go of its data here instead, while the buffers that VTK
  // frees come back to this tracer (those no one references any more).
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* output = outInfo ? outInfo->Get(vtkDataObject::DATA_OBJECT()) : nullptr;
  if (output && request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_NOT_GENERATED()))
  {
    this->Returned->SetExpecting(true);
    output->PrepareForNewData();
    this->Returned->SetExpecting(false);
  }
  // Memory that cannot be had fails the request with a message, instead of
  // aborting the caller's process (VTK's executives do not catch).
  try
  {
    return this->Superclass::ProcessRequest(request, inputVector, outputVector);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("ran out of memory tracing " << this->NumberOfParticles
                                               << " particles: trace fewer, or set a MemoryLimit "
                                                  "(the pipeline then traces in batches)");
    return 0;
  }
}

// [first, end) of the run, and this piece's share of it; false (with an
// error) when the counts are out of range or the hits would not fit.
bool vtkBrumeLightTracer::PlanParticles(vtkInformation* outInfo, ParticleRange& range)
{
  range.Particles = this->NumberOfParticles;
  if (range.Particles < 1 || range.Particles > vtkTypeInt64(10000000000LL))
  {
    vtkErrorMacro("NumberOfParticles must be in [1, 1e10], not " << range.Particles << ".");
    return false;
  }
  range.End = this->EndParticle > 0 ? this->EndParticle : range.Particles;
  if (range.End > range.Particles)
  {
    vtkErrorMacro("EndParticle must be in [1, NumberOfParticles = "
      << range.Particles << "] (or 0: " << range.Particles << "), not " << range.End << ".");
    return false;
  }
  range.First = this->FirstParticle;
  if (range.First < 0 || range.First >= range.End)
  {
    vtkErrorMacro("FirstParticle must be in [0, EndParticle - 1 = " << range.End - 1 << "], not "
                                                                    << range.First << ".");
    return false;
  }
  // A piece of the pipeline (one process of a distributed run) traces its
  // share of [FirstParticle, EndParticle); each particle's stream
  // depends only on (seed, index), so the pieces together are the whole run.
  const int piece = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? std::max(1, outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
    : 1;
  const vtkTypeInt64 runFirst = range.First;
  range.PieceFirst = runFirst + (range.End - runFirst) * piece / pieces;
  range.PieceEnd = runFirst + (range.End - runFirst) * (piece + 1) / pieces;
  const vtkTypeInt64 traced = range.PieceEnd - range.PieceFirst;
  const double expectedBytes = ExpectedHitBytes(traced);
  if (expectedBytes > static_cast<double>(this->MemoryLimit))
  {
    vtkErrorMacro("" << traced << " particles would need about " << expectedBytes / (1 << 20)
                     << " MiB of hits, more than MemoryLimit (" << this->MemoryLimit / (1 << 20)
                     << " MiB).");
    return false;
  }
  return true;
}

// Traces this piece's particles in up to twenty batches of blocks, each
// batch's hits copied into the output's arrays as they come; false (with an
// error) when they cannot be stored.
bool vtkBrumeLightTracer::TraceBatches(const brume::LightTracer& tracer, const ParticleRange& range,
  BatchMemory& memory, vtkBrumeLightTracerOutput& out, brume::TraceCounters& sum, vtkIdType& stored)
{
  const vtkTypeInt64 traced = range.PieceEnd - range.PieceFirst;
  const vtkTypeInt64 blocks = (traced + ParticlesPerBlock - 1) / ParticlesPerBlock;
  std::vector<std::vector<brume::Hit>>& blockHits = memory.BlockHits;
  std::vector<brume::TraceCounters> counters;
  const vtkTypeInt64 batches = std::min<vtkTypeInt64>(blocks, 20);
  stored = 0;
  for (vtkTypeInt64 k = 0; k < batches && !this->GetAbortExecute(); ++k)
  {
    const vtkTypeInt64 begin = blocks * k / batches, end = blocks * (k + 1) / batches;
    // Block buffers are reused from batch to batch: their pages are already
    // mapped, so storing a hit costs no page fault.
    blockHits.resize(static_cast<std::size_t>(end - begin));
    for (auto& block : blockHits)
    {
      block.clear();
    }
    counters.assign(static_cast<std::size_t>(end - begin), {});
    TraceBlocks functor{ tracer, blockHits, counters, range.Particles, range.PieceFirst,
      range.PieceEnd, begin };
    vtkSMPTools::For(0, end - begin, functor);
    std::size_t batchHits = 0;
    for (std::size_t b = 0; b < blockHits.size(); ++b)
    {
      batchHits += blockHits[b].size();
      sum.Add(counters[b]);
    }
    // After the first batch, room for the hits all batches will likely
    // hold (its hits per particle, 5 % more): one allocation, not twenty.
    const bool firstBatch = k == 0 && batches > 1;
    const vtkIdType expected = firstBatch
      ? static_cast<vtkIdType>(1.05 * static_cast<double>(batchHits) * static_cast<double>(blocks) /
          static_cast<double>(end - begin)) +
        1024
      : 0;
    if (!(firstBatch ? out.Reallocate(std::max<vtkIdType>(expected, stored + batchHits))
                     : out.Resize(stored + static_cast<vtkIdType>(batchHits))))
    {
      vtkErrorMacro("Out of memory storing " << stored + batchHits << " particle hits.");
      return false;
    }
    // Copy the blocks to their places in parallel.
    std::vector<vtkIdType> offsets(blockHits.size() + 1, stored);
    for (std::size_t b = 0; b < blockHits.size(); ++b)
    {
      offsets[b + 1] = offsets[b] + static_cast<vtkIdType>(blockHits[b].size());
    }
    vtkSMPTools::For(0, static_cast<vtkIdType>(blockHits.size()),
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType b = first; b < last; ++b)
        {
          out.Write(offsets[b], blockHits[b]);
        }
      });
    stored = offsets.back();
    this->UpdateProgress(0.99 * static_cast<double>(k + 1) / static_cast<double>(batches));
  }
  return true;
}

namespace
{
void AddValue(vtkPolyData* output, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  output->GetFieldData()->AddArray(a);
}

// What the reconstruction reads of the run beside the hits: the emitted
// power, the aimed lights' weights, the run's and this piece's particles,
// the seed, the rays and the energy balance.
void WriteRunFields(vtkPolyData* output, const brume::Scene& scene,
  const brume::LightTracer& tracer, bool aims, const vtkTypeInt64 range[5], vtkIdType seed,
  const brume::TraceCounters& sum)
{
  AddTuple(output, vtkBrumeHitConversion::TotalPowerName, tracer.GetTotalPower());
  if (aims)
  {
    // The weight of each class of Aim, emitter id by emitter id: the
    // objects' (emissive surfaces are never aimed), then the lights'.
    vtkNew<vtkDoubleArray> weights;
    weights->SetName(vtkBrumeHitConversion::AimWeightsName);
    weights->SetNumberOfComponents(3);
    for (std::size_t o = 0; o < scene.NumberOfObjects(); ++o)
    {
      weights->InsertNextTuple3(1.0, 1.0, 1.0);
    }
    for (const brume::Light& l : scene.Lights)
    {
      weights->InsertNextTuple3(l.EmissionWeight(0), l.EmissionWeight(1), l.EmissionWeight(2));
    }
    output->GetFieldData()->AddArray(weights);
  }
  AddValue(output, vtkBrumeHitConversion::NumberOfParticlesName, static_cast<double>(range[0]));
  AddValue(output, vtkBrumeHitConversion::FirstParticleName, static_cast<double>(range[1]));
  AddValue(output, vtkBrumeHitConversion::EndParticleName, static_cast<double>(range[2]));
  vtkNew<vtkDoubleArray> pieceRange;
  pieceRange->SetName(vtkBrumeNames::PieceParticles); // [first, end) traced by this piece
  pieceRange->SetNumberOfComponents(2);
  pieceRange->InsertNextTuple2(static_cast<double>(range[3]), static_cast<double>(range[4]));
  output->GetFieldData()->AddArray(pieceRange);
  AddValue(output, vtkBrumeHitConversion::SeedName, static_cast<double>(seed));
  AddValue(output, vtkBrumeNames::NumberOfRays, static_cast<double>(sum.Rays));
  AddTuple(output, vtkBrumeNames::EmittedFlux, sum.Emitted);
  AddTuple(output, vtkBrumeNames::AbsorbedFlux, sum.Absorbed);
  AddTuple(output, vtkBrumeNames::EscapedFlux, sum.Escaped);
  AddTuple(output, vtkBrumeNames::TruncatedFlux, sum.Truncated);
  AddTuple(output, vtkBrumeNames::EstimatorNetFlux, sum.EstimatorNet);
}
}

int vtkBrumeLightTracer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto collection =
    vtkBrumeSceneConversion::AsCollection(vtkDataObject::GetData(inputVector[0], 0));
  vtkPartitionedDataSetCollection* input = collection;
  auto* output = vtkPolyData::GetData(outputVector, 0);
  this->LastRayCount = 0;
  this->LastReusedBytes = 0;
  // The buffers of the last output that came back (ProcessRequest): written
  // again below, or freed at any return.
  vtkBrumeLightTracerOutput out;
  const std::size_t returnedBytes = out.Adopt(*this->Returned);
  std::unique_ptr<BatchMemory> reused = std::move(this->Reused);

  ParticleRange range;
  if (!this->PlanParticles(outputVector->GetInformationObject(0), range))
  {
    return 0;
  }
  const vtkTypeInt64 traced = range.PieceEnd - range.PieceFirst;

  brume::Scene scene;
  if (!vtkBrumeSceneConversion::ToTracedScene(this, input, this->Seed, this->Lights, scene))
  {
    return 0;
  }
  this->Densities.clear();
  for (const brume::Medium& medium : scene.Media)
  {
    if (medium.Density)
    {
      this->Densities.push_back(medium.Density);
    }
  }
  // The switched-on vtkLights come last among the scene's lights; the
  // output names them for the reconstruction, which sees only the scene.
  std::size_t given = 0;
  this->Lights->InitTraversal();
  while (vtkLight* light = this->Lights->GetNextItem())
  {
    given += light->GetSwitch() ? 1 : 0;
  }
  const std::vector<brume::Light> givenLights(scene.Lights.end() - given, scene.Lights.end());
  // The BVH the reconstruction's shadow rays keep (from the last batch,
  // time step or refinement) while the surfaces are the same. Not kept
  // here: a filter may outlive Embree (ParaView deletes its proxies while
  // the process exits).
  const std::shared_ptr<const brume::RayCaster> shared =
    vtkBrumeSceneConversion::SharedRayCaster(scene);
  const brume::RayCaster& caster = *shared;
  if (!caster.GetError().empty())
  {
    vtkErrorMacro("Could not build the ray-casting structure: " << caster.GetError());
    return 0;
  }
  brume::AimAtMedia(scene, caster, static_cast<float>(this->MediumAimFraction));
  const bool aims = std::any_of(
    scene.Lights.begin(), scene.Lights.end(), [](const brume::Light& l) { return l.Aims(); });
  brume::TraceSettings settings;
  settings.Seed = static_cast<std::uint64_t>(this->Seed);
  settings.MaxDepth = this->MaximumDepth;
  settings.RouletteDepth = this->RouletteDepth;
  settings.SplitHeavyParticles = this->SplitHeavyParticles;
  const brume::LightTracer tracer(scene, caster, settings);

  // Output arrays, grown batch by batch (realloc of large blocks moves pages
  // without copying), so the hits are never held twice. Each execution (the
  // next batch of a run, or a new run: another seed, count or scene)
  // writes where the last output's hits were, when no one else holds them
  // any more: a fresh page costs a fault on first touch (microseconds
  // each), and 10^6 particles of the default scene fill 121 MB.
  if (!reused)
  {
    reused.reset(new BatchMemory);
  }
  out.WithAim = aims;
  output->Initialize();
  // A run much smaller than the last keeps no more of its memory than twice
  // the hits it is expected to store: as many a particle as the last run
  // stored, or ExpectedHitBytes' four, whichever is more.
  const double hitsPerParticle = std::max(4.0, this->LastHitsPerParticle);
  out.Cap(static_cast<vtkIdType>(2.0 * hitsPerParticle * static_cast<double>(traced)));
  this->LastReusedBytes = static_cast<vtkTypeInt64>(returnedBytes);
  brume::TraceCounters sum;
  vtkIdType stored = 0;
  if (!this->TraceBatches(tracer, range, *reused, out, sum, stored))
  {
    return 0;
  }
  this->LastRayCount = static_cast<vtkTypeInt64>(sum.Rays);
  // The block buffers are kept for the next batch only while the run goes
  // on; the output's buffers come back to any next execution.
  const bool runGoesOn = range.End < range.Particles && !this->GetAbortExecute();
  out.Attach(output, stored, this->Returned.get());
  this->LastHitsPerParticle = static_cast<double>(stored) / static_cast<double>(traced);
  if (runGoesOn)
  {
    this->Reused = std::move(reused);
  }
  const vtkTypeInt64 fields[5] = { range.Particles, range.First, range.End, range.PieceFirst,
    range.PieceEnd };
  WriteRunFields(output, scene, tracer, aims, fields, this->Seed, sum);
  vtkBrumeSceneConversion::AppendFieldLights(givenLights, output->GetFieldData());
  this->UpdateProgress(1.0);
  return 1;
}

void vtkBrumeLightTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "FirstParticle: " << this->FirstParticle << "\n";
  os << indent << "EndParticle: " << this->EndParticle << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumDepth: " << this->MaximumDepth << "\n";
  os << indent << "RouletteDepth: " << this->RouletteDepth << "\n";
  os << indent << "MediumAimFraction: " << this->MediumAimFraction << "\n";
  os << indent << "SplitHeavyParticles: " << this->SplitHeavyParticles << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
}
