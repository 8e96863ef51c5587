// SPDX-License-Identifier: BSD-3-Clause
// Scene files and OpenVDB input:
//   TestSceneFiles roundtrip DIR SCENE TF_SCENE
//                                   default scene -> writer -> reader traces the same hits,
//                                   and Data/scenes/cornell-fog.json does too; so does a
//                                   scene with a transfer-function medium
//   TestSceneFiles openvdb DIR [SHARED_VDB_DIR]
//                                   a grid this test writes, read back voxel by voxel;
//                                   corrupt copies fail cleanly; the shared samples
//                                   (when present) read with finite, non-negative values
//   TestSceneFiles meshes DIR       one quad written in every surface format and encoding
//                                   the scene files accept reads back as its two triangles
//   TestSceneFiles appended DIR     a volume and meshes in VTK XML's appended data (what VTK's
//                                   and ParaView's writers give by default), raw, encoded and
//                                   compressed, read back value for value, whatever the
//                                   expat (Debian 12's updates defer reparsing, which VTK 9.2's
//                                   own readers do not survive)
//   TestSceneFiles shared SCENES SHARED_VDB_DIR
//                                   the measurement scenes built on the shared volumes
//                                   (Testing/Data/SharedVdbScenes) read, and their light
//                                   reaches their medium; skipped without the volumes
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeHitConversion.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeOpenVDBReader.h"
#include "vtkBrumeSceneReader.h"
#include "vtkBrumeSceneWriter.h"
#include "vtkBrumeXMLReaders.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOBJWriter.h"
#include "vtkPLYWriter.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkStringArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include "BrumeVdbWriter.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
int failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

// Traces a scene with a fixed seed; the hits as points plus the flux.
vtkSmartPointer<vtkPolyData> Trace(vtkAlgorithm* source)
{
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(source->GetOutputPort());
  tracer->SetNumberOfParticles(20000);
  tracer->SetSeed(7);
  tracer->Update();
  auto hits = vtkSmartPointer<vtkPolyData>::New();
  hits->ShallowCopy(tracer->GetOutput());
  return hits;
}

bool SameHits(vtkPolyData* a, vtkPolyData* b)
{
  if (a->GetNumberOfPoints() == 0 || a->GetNumberOfPoints() != b->GetNumberOfPoints())
  {
    std::cerr << "hit counts " << a->GetNumberOfPoints() << " and " << b->GetNumberOfPoints()
              << "\n";
    return false;
  }
  vtkDataArray* fa = a->GetPointData()->GetArray(vtkBrumeNames::Flux);
  vtkDataArray* fb = b->GetPointData()->GetArray(vtkBrumeNames::Flux);
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double pa[3], pb[3];
    a->GetPoint(i, pa);
    b->GetPoint(i, pb);
    for (int c = 0; c < 3; ++c)
    {
      if (pa[c] != pb[c] || fa->GetComponent(i, c) != fb->GetComponent(i, c))
      {
        std::cerr << "hit " << i << " differs\n";
        return false;
      }
    }
  }
  return true;
}

int RoundTrip(
  const std::string& dir, const std::string& shippedScene, const std::string& transferFunctionScene)
{
  vtkNew<vtkBrumeDefaultSceneSource> builtIn;
  builtIn->Update();
  const std::string file = dir + "/roundtrip.json";
  vtkNew<vtkBrumeSceneWriter> writer;
  writer->SetInputConnection(builtIn->GetOutputPort());
  writer->SetFileName(file.c_str());
  Check(writer->Write() == 1, "the writer saves the default scene");

  vtkNew<vtkBrumeSceneReader> reader;
  reader->SetFileName(file.c_str());
  Check(reader->GetExecutive()->Update() == 1, "the reader reads what the writer wrote");
  const auto expected = Trace(builtIn);
  Check(SameHits(expected, Trace(reader)), "written and read back, the scene traces the same hits");

  // Camera and render settings survive too.
  vtkDataArray* camera =
    reader->GetOutputDataObject(0)->GetFieldData()->GetArray(vtkBrumeNames::CameraPosition);
  Check(camera && camera->GetComponent(0, 2) == 4.0, "the camera position survives the round trip");

  vtkNew<vtkBrumeSceneReader> shipped;
  shipped->SetFileName(shippedScene.c_str());
  Check(shipped->GetExecutive()->Update() == 1, "Data/scenes/cornell-fog.json reads");
  Check(SameHits(expected, Trace(shipped)), "cornell-fog.json traces the built-in scene's hits");

  // What ParaView's reader factory asks: scene files yes, other JSON no.
  Check(vtkBrumeSceneReader::CanReadFile(file.c_str()) == 1, "CanReadFile: a written scene");
  Check(
    vtkBrumeSceneReader::CanReadFile(shippedScene.c_str()) == 1, "CanReadFile: cornell-fog.json");
  const std::string other = dir + "/not-a-scene.json";
  std::ofstream(other) << R"({ "name": "a JSON file of another program", "size": [1, 2] })";
  Check(vtkBrumeSceneReader::CanReadFile(other.c_str()) == 0, "CanReadFile: another JSON file");
  Check(vtkBrumeSceneReader::CanReadFile((dir + "/missing.json").c_str()) == 0,
    "CanReadFile: a missing file");
  Check(vtkBrumeSceneReader::CanReadFile(nullptr) == 0, "CanReadFile: no name");

  // A medium classified by a transfer function (its array, points, unit
  // distance, interpolation and the albedo) survives the round trip, on an
  // image and on an OpenVDB grid (TF_SCENE with -vdb before .json).
  const std::string vdbScene =
    transferFunctionScene.substr(0, transferFunctionScene.size() - 5) + "-vdb.json";
  int written = 0;
  for (const std::string& scene : { transferFunctionScene, vdbScene })
  {
    vtkNew<vtkBrumeSceneReader> classified;
    classified->SetFileName(scene.c_str());
    Check(classified->GetExecutive()->Update() == 1, "the transfer-function scene reads: " + scene);
    const std::string classifiedFile =
      dir + "/roundtrip-transfer-function-" + std::to_string(written++) + ".json";
    vtkNew<vtkBrumeSceneWriter> classifiedWriter;
    classifiedWriter->SetInputConnection(classified->GetOutputPort());
    classifiedWriter->SetFileName(classifiedFile.c_str());
    Check(classifiedWriter->Write() == 1, "the writer saves the transfer-function scene");
    vtkNew<vtkBrumeSceneReader> classifiedBack;
    classifiedBack->SetFileName(classifiedFile.c_str());
    Check(classifiedBack->GetExecutive()->Update() == 1, "the written transfer function reads");
    Check(SameHits(Trace(classified), Trace(classifiedBack)),
      "written and read back, the transfer-function scene traces the same hits: " + scene);
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// Two grids with known values: density = 0.01 (i + 2 j + 4 k) on the box
// [2, 9] x [-3, 4] x [0, 5] of voxels 0.5 wide, translated by (1, 2, 3);
// temperature constant 300 on a smaller box.
void WriteGrids(const std::string& path)
{
  brume::vdbwriter::Grid density;
  density.VoxelSize = 0.5;
  density.Translation = { 1.0, 2.0, 3.0 };
  density.Lower = { 2, -3, 0 };
  density.Upper = { 9, 4, 5 };
  density.Value = [](int i, int j, int k)
  { return 0.01f * static_cast<float>(i + 2 * j + 4 * k + 20); };
  brume::vdbwriter::Grid temperature = density;
  temperature.Name = "temperature";
  temperature.Lower = { 0, 0, 0 };
  temperature.Upper = { 3, 3, 3 };
  temperature.Value = [](int, int, int) { return 300.0f; };
  brume::vdbwriter::Write(path, { density, temperature });
}

int OpenVDB(const std::string& dir, const std::string& shared)
{
  const std::string file = dir + "/two-grids.vdb";
  WriteGrids(file);

  vtkNew<vtkBrumeOpenVDBReader> reader;
  reader->SetFileName(file.c_str());
  reader->UpdateInformation();
  vtkStringArray* names = reader->GetGridNames();
  Check(names->GetNumberOfValues() == 2 && names->GetValue(0) == "density" &&
      names->GetValue(1) == "temperature",
    "the reader lists both grids");
  reader->SetGridName("density");
  Check(reader->GetExecutive()->Update() == 1, "the density grid reads");
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  double origin[3], spacing[3];
  image->GetDimensions(dims);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  Check(dims[0] == 8 && dims[1] == 8 && dims[2] == 6, "the image covers the active voxels");
  Check(origin[0] == 2.0 && origin[1] == 0.5 && origin[2] == 3.0 && spacing[0] == 0.5,
    "the grid transform places the image");
  vtkDataArray* values = image->GetPointData()->GetScalars();
  bool exact = values != nullptr;
  for (int k = 0; exact && k < dims[2]; ++k)
    for (int j = 0; exact && j < dims[1]; ++j)
      for (int i = 0; exact && i < dims[0]; ++i)
      {
        const float expected = 0.01f * static_cast<float>((i + 2) + 2 * (j - 3) + 4 * k + 20);
        exact = values->GetComponent(i + dims[0] * (j + dims[1] * k), 0) == expected;
      }
  Check(exact, "every voxel value comes through");

  reader->SetDownsample(2);
  reader->Update();
  reader->GetOutput()->GetDimensions(dims);
  Check(dims[0] == 4 && dims[1] == 4 && dims[2] == 3 && reader->GetOutput()->GetSpacing()[0] == 1.0,
    "downsampling keeps every second voxel");
  reader->SetDownsample(1);
  reader->SetMemoryLimit(100);
  Check(reader->GetExecutive()->Update() == 0, "a dense copy over the memory cap fails");
  reader->SetMemoryLimit(vtkTypeInt64(1) << 30);
  reader->SetGridName("temperature");
  Check(reader->GetExecutive()->Update() == 1 && reader->GetOutput()->GetNumberOfPoints() == 64 &&
      reader->GetOutput()->GetPointData()->GetScalars()->GetRange()[0] == 300.0,
    "the temperature grid reads");
  reader->SetGridName("pressure");
  Check(reader->GetExecutive()->Update() == 0, "a missing grid fails");

  // A scene medium from the grid without a box: the grid's active box,
  // widened by one voxel (i 2..9, j -3..4, k 0..5; 0.5 wide, moved by (1, 2, 3)).
  {
    const std::string scenePath = dir + "/vdb-without-box.json";
    std::ofstream(scenePath) << R"({ "brume_scene": 1,
  "surfaces": [ { "name": "floor", "quad": [[0, 0, 0], [0, 0, 8], [8, 0, 8], [8, 0, 0]] } ],
  "media": [ { "name": "smoke", "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1],
               "density": { "vdb": "two-grids.vdb", "grid": "density" } } ],
  "lights": [ { "type": "point", "position": [4, 8, 4], "intensity": [10, 10, 10] } ] })";
    vtkNew<vtkBrumeSceneReader> sceneReader;
    sceneReader->SetFileName(scenePath.c_str());
    const bool read = sceneReader->GetExecutive()->Update() == 1;
    Check(read, "an OpenVDB medium needs no box");
    if (read)
    {
      double b[6];
      vtkImageData::SafeDownCast(
        sceneReader->GetOutput()->GetPartitionedDataSet(1)->GetPartition(0))
        ->GetBounds(b);
      const double expected[6] = { 1.5, 6.0, 0.0, 4.5, 2.5, 6.0 };
      bool same = true;
      for (int a = 0; a < 6; ++a)
      {
        same = same && std::abs(b[a] - expected[a]) < 1e-5;
      }
      Check(same, "the medium's box is the grid's active box");
    }
  }

  // Corrupt copies: cut, garbage after the header, not a VDB, absent.
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::pair<std::string, std::string> corrupt[] = {
    { "cut-half.vdb", bytes.substr(0, bytes.size() / 2) },
    { "cut-header.vdb", bytes.substr(0, 64) }, { "empty.vdb", "" },
    { "noise.vdb", bytes.substr(0, 8) + std::string(4000, '\x7f') }, { "text.vdb", "not a vdb\n" }
  };
  for (const auto& c : corrupt)
  {
    const std::string path = dir + "/" + c.first;
    std::ofstream(path, std::ios::binary) << c.second;
    vtkNew<vtkBrumeOpenVDBReader> bad;
    bad->SetFileName(path.c_str());
    Check(bad->GetExecutive()->Update() == 0, c.first + " fails cleanly");
  }
  vtkNew<vtkBrumeOpenVDBReader> missing;
  missing->SetFileName((dir + "/no-such-file.vdb").c_str());
  Check(missing->GetExecutive()->Update() == 0, "a missing file fails");

  // The public samples, where this checkout has them.
  if (!shared.empty() && std::filesystem::is_directory(shared))
  {
    for (const auto& entry : std::filesystem::directory_iterator(shared))
    {
      if (entry.path().extension() != ".vdb")
      {
        continue;
      }
      vtkNew<vtkBrumeOpenVDBReader> sample;
      sample->SetFileName(entry.path().string().c_str());
      sample->SetDownsample(4);
      const bool ok = sample->GetExecutive()->Update() == 1;
      double range[2] = { -1, -1 };
      if (ok && sample->GetOutput()->GetPointData()->GetScalars())
      {
        sample->GetOutput()->GetPointData()->GetScalars()->GetRange(range);
      }
      std::cout << entry.path().filename().string() << ": " << (ok ? "read" : "failed")
                << ", range " << range[0] << " to " << range[1] << "\n";
      Check(ok && std::isfinite(range[0]) && std::isfinite(range[1]) && range[1] > 0.0 &&
          range[0] >= 0.0,
        entry.path().string() + " reads with finite values");
    }
  }
  else
  {
    std::cout << "no shared sample volumes: skipped them\n";
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// A scene whose only surface is `mesh` (a file beside it) under a point light.
std::string MeshScene(const std::string& mesh)
{
  return R"({"brume_scene": 1,
  "camera": {"position": [0, 0, 4], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle": 40},
  "surfaces": [{"name": "quad", "file": ")" +
    mesh + R"(", "material": {"reflectance": [0.5, 0.5, 0.5]}}],
  "lights": [{"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]}]})";
}

int Meshes(const std::string& dir)
{
  // The unit square at z = 0 as two triangles.
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(1, 1, 0);
  points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType t0[3] = { 0, 1, 2 }, t1[3] = { 0, 2, 3 };
  triangles->InsertNextCell(3, t0);
  triangles->InsertNextCell(3, t1);
  vtkNew<vtkPolyData> quad;
  quad->SetPoints(points);
  quad->SetPolys(triangles);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->InsertNextCell(VTK_TRIANGLE, 3, t0);
  grid->InsertNextCell(VTK_TRIANGLE, 3, t1);

  auto write = [&](auto& writer, vtkDataObject* data, const std::string& name)
  {
    writer->SetInputData(data);
    writer->SetFileName((dir + "/" + name).c_str());
    Check(writer->Write() == 1, "writes " + name);
  };
  vtkNew<vtkOBJWriter> obj;
  write(obj, quad, "quad.obj");
  vtkNew<vtkPLYWriter> plyText, plyBinary;
  plyText->SetFileTypeToASCII();
  write(plyText, quad, "quad-ascii.ply");
  plyBinary->SetFileTypeToBinary();
  write(plyBinary, quad, "quad-binary.ply");
  vtkNew<vtkSTLWriter> stlText, stlBinary;
  stlText->SetFileTypeToASCII();
  write(stlText, quad, "quad-ascii.stl");
  stlBinary->SetFileTypeToBinary();
  write(stlBinary, quad, "quad-binary.stl");
  vtkNew<vtkXMLPolyDataWriter> vtpText, vtpRaw, vtpZlib;
  vtpText->SetDataModeToAscii();
  write(vtpText, quad, "quad-ascii.vtp");
  vtpRaw->SetDataModeToAppended();
  vtpRaw->EncodeAppendedDataOff();
  vtpRaw->SetCompressorTypeToNone();
  write(vtpRaw, quad, "quad-raw.vtp");
  vtpZlib->SetCompressorTypeToZLib();
  write(vtpZlib, quad, "quad-zlib.vtp");
  vtkNew<vtkXMLUnstructuredGridWriter> vtuText, vtuZlib;
  vtuText->SetDataModeToAscii();
  write(vtuText, grid, "quad-ascii.vtu");
  vtuZlib->SetCompressorTypeToZLib();
  write(vtuZlib, grid, "quad-zlib.vtu");

  // A header comment in UTF-8 (names and keywords must be ASCII, comments not).
  std::ofstream(dir + "/quad-comment.ply")
    << "ply\nformat ascii 1.0\ncomment cr\xc3\xa9\xc3\xa9 par Brume\nelement vertex 4\n"
       "property float x\nproperty float y\nproperty float z\nelement face 2\n"
       "property list uchar int vertex_indices\nend_header\n"
       "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  for (const char* mesh : { "quad.obj", "quad-ascii.ply", "quad-binary.ply", "quad-comment.ply",
         "quad-ascii.stl", "quad-binary.stl", "quad-ascii.vtp", "quad-raw.vtp", "quad-zlib.vtp",
         "quad-ascii.vtu", "quad-zlib.vtu" })
  {
    const std::string scene = dir + "/" + mesh + ".json";
    std::ofstream(scene) << MeshScene(mesh);
    vtkNew<vtkBrumeSceneReader> reader;
    reader->SetFileName(scene.c_str());
    const bool ok = reader->GetExecutive()->Update() == 1;
    Check(ok, std::string("a scene naming ") + mesh + " reads");
    auto* collection =
      vtkPartitionedDataSetCollection::SafeDownCast(reader->GetOutputDataObject(0));
    vtkPolyData* surface = nullptr;
    if (ok && collection && collection->GetNumberOfPartitionedDataSets() > 0 &&
      collection->GetPartitionedDataSet(0)->GetNumberOfPartitions() > 0)
    {
      surface = vtkPolyData::SafeDownCast(collection->GetPartitionedDataSet(0)->GetPartition(0));
    }
    double bounds[6] = { 0, -1, 0, -1, 0, -1 };
    if (surface)
    {
      surface->GetBounds(bounds);
    }
    std::cout << mesh << ": " << (surface ? surface->GetNumberOfPolys() : -1) << " triangles, x "
              << bounds[0] << " to " << bounds[1] << ", y " << bounds[2] << " to " << bounds[3]
              << "\n";
    Check(surface && surface->GetNumberOfPolys() == 2 && bounds[0] == 0.0 && bounds[1] == 1.0 &&
        bounds[2] == 0.0 && bounds[3] == 1.0 && bounds[4] == 0.0 && bounds[5] == 0.0,
      std::string(mesh) + " reads back as the quad's two triangles");
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// The same data as appended, raw or base64-encoded, uncompressed or
// compressed (zlib, LZ4, LZMA), and as inline binary, through a scene: a
// volume of 72^3 floats (1.5 MB, many parse buffers of VTK's reader; any
// that holds more than one failed under a deferring expat; compressed, it
// is read on every thread, in blocks of 1,000 bytes, so that groups of
// blocks start within base64's triplets and the last block is partial)
// read back value for value, and a mesh of 2,000 triangles as .vtp and
// .vtu. A compressed volume with a corrupt block does not read.
int Appended(const std::string& dir)
{
  constexpr int n = 72;
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(n, n, n);
  volume->SetOrigin(-1, -1, -1);
  volume->SetSpacing(2.0 / (n - 1), 2.0 / (n - 1), 2.0 / (n - 1));
  vtkNew<vtkFloatArray> scalar;
  scalar->SetName("scalar");
  scalar->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  // Bytes of every value (a hash of the index), as measured data has.
  for (vtkIdType i = 0; i < scalar->GetNumberOfTuples(); ++i)
  {
    const auto h = static_cast<std::uint32_t>(i) * 2654435761u;
    scalar->SetValue(i, static_cast<float>(h >> 8) / static_cast<float>(1u << 24));
  }
  volume->GetPointData()->AddArray(scalar);

  // A strip of 1,000 quads (2,000 triangles) in the unit square.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  constexpr int strip = 1000;
  for (int i = 0; i <= strip; ++i)
  {
    points->InsertNextPoint(static_cast<double>(i) / strip, 0, 0);
    points->InsertNextPoint(static_cast<double>(i) / strip, 1, 0);
  }
  for (vtkIdType i = 0; i < strip; ++i)
  {
    const vtkIdType a[3] = { 2 * i, 2 * i + 2, 2 * i + 3 }, b[3] = { 2 * i, 2 * i + 3, 2 * i + 1 };
    triangles->InsertNextCell(3, a);
    triangles->InsertNextCell(3, b);
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(VTK_TRIANGLE, triangles);

  struct Mode
  {
    const char* name;
    bool appended, encoded;
    int compressor;
  };
  const Mode modes[] = { { "raw", true, false, vtkXMLWriter::NONE },
    { "raw-zlib", true, false, vtkXMLWriter::ZLIB }, { "raw-lz4", true, false, vtkXMLWriter::LZ4 },
    { "raw-lzma", true, false, vtkXMLWriter::LZMA }, { "base64", true, true, vtkXMLWriter::NONE },
    { "base64-zlib", true, true, vtkXMLWriter::ZLIB },
    { "inline", false, false, vtkXMLWriter::NONE } };
  auto configure = [](vtkXMLWriter* writer, const Mode& mode)
  {
    if (mode.appended)
    {
      writer->SetDataModeToAppended();
    }
    else
    {
      writer->SetDataModeToBinary();
    }
    writer->SetEncodeAppendedData(mode.encoded);
    writer->SetCompressorType(mode.compressor);
    writer->SetBlockSize(1000);
  };
  for (const Mode& mode : modes)
  {
    const std::string stem = std::string("xml-") + mode.name;
    vtkNew<vtkXMLImageDataWriter> volumeWriter;
    vtkNew<vtkXMLPolyDataWriter> meshWriter;
    vtkNew<vtkXMLUnstructuredGridWriter> gridWriter;
    configure(volumeWriter, mode);
    configure(meshWriter, mode);
    configure(gridWriter, mode);
    volumeWriter->SetInputData(volume);
    volumeWriter->SetFileName((dir + "/" + stem + ".vti").c_str());
    meshWriter->SetInputData(mesh);
    meshWriter->SetFileName((dir + "/" + stem + ".vtp").c_str());
    gridWriter->SetInputData(grid);
    gridWriter->SetFileName((dir + "/" + stem + ".vtu").c_str());
    Check(volumeWriter->Write() == 1 && meshWriter->Write() == 1 && gridWriter->Write() == 1,
      stem + ": written");

    const std::string scene = dir + "/" + stem + ".json";
    std::ofstream(scene) << R"({"brume_scene": 1,
  "camera": {"position": [0, 0, 4], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle": 40},
  "surfaces": [{"name": "strip", "file": ")"
                         << stem << R"(.vtp", "material": {"reflectance": [0.5, 0.5, 0.5]}},
    {"name": "grid", "file": ")"
                         << stem << R"(.vtu", "material": {"reflectance": [0.5, 0.5, 0.5]}}],
  "media": [{"name": "fog", "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "g": 0,
    "density": {"vti": ")"
                         << stem << R"(.vti", "array": "scalar"}}],
  "lights": [{"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]}]})";
    vtkNew<vtkBrumeSceneReader> reader;
    reader->SetFileName(scene.c_str());
    const bool ok = reader->GetExecutive()->Update() == 1;
    Check(ok, stem + ": the scene reads");
    auto* collection =
      vtkPartitionedDataSetCollection::SafeDownCast(reader->GetOutputDataObject(0));
    auto part = [&](unsigned int i) -> vtkDataObject*
    {
      return ok && collection && collection->GetNumberOfPartitionedDataSets() > i &&
          collection->GetPartitionedDataSet(i)->GetNumberOfPartitions() > 0
        ? collection->GetPartitionedDataSet(i)->GetPartition(0)
        : nullptr;
    };
    auto* strip0 = vtkPolyData::SafeDownCast(part(0));
    auto* strip1 = vtkPolyData::SafeDownCast(part(1));
    auto* fog = vtkImageData::SafeDownCast(part(2));
    auto* values =
      fog ? vtkFloatArray::SafeDownCast(fog->GetPointData()->GetArray("scalar")) : nullptr;
    vtkIdType same = 0;
    for (vtkIdType i = 0; values && i < values->GetNumberOfTuples() &&
         values->GetNumberOfTuples() == scalar->GetNumberOfTuples();
         ++i)
    {
      same += values->GetValue(i) == scalar->GetValue(i) ? 1 : 0;
    }
    std::cout << stem << ": .vtp " << (strip0 ? strip0->GetNumberOfPolys() : -1)
              << " triangles, .vtu " << (strip1 ? strip1->GetNumberOfPolys() : -1)
              << " triangles, .vti " << same << " of " << scalar->GetNumberOfTuples()
              << " values as written\n";
    Check(strip0 && strip0->GetNumberOfPolys() == 2 * strip, stem + ".vtp: every triangle");
    Check(strip1 && strip1->GetNumberOfPolys() == 2 * strip, stem + ".vtu: every triangle");
    Check(same == scalar->GetNumberOfTuples(), stem + ".vti: every value as written");
    if (mode.compressor == vtkXMLWriter::ZLIB && mode.appended)
    {
      // Read on every thread, the volume moves the reader's progress as it
      // goes (as VTK's own reading does), and an abort within the read
      // stops it: the array is not given.
      struct Watch
      {
        std::vector<double> Progress;
        vtkAlgorithm* AbortAt = nullptr;
      } watch;
      vtkNew<vtkCallbackCommand> progress;
      progress->SetClientData(&watch);
      progress->SetCallback(
        [](vtkObject* caller, unsigned long, void* data, void* call)
        {
          auto* w = static_cast<Watch*>(data);
          const double p = *static_cast<double*>(call);
          w->Progress.push_back(p);
          if (w->AbortAt && p > 0.0 && p < 1.0)
          {
            static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
          }
        });
      vtkNew<vtkBrumeXMLImageDataReader> direct;
      direct->SetFileName((dir + "/" + stem + ".vti").c_str());
      direct->AddObserver(vtkCommand::ProgressEvent, progress);
      direct->Update();
      std::size_t within = 0;
      bool rising = true;
      for (std::size_t k = 0; k < watch.Progress.size(); ++k)
      {
        within += watch.Progress[k] > 0.0 && watch.Progress[k] < 1.0 ? 1 : 0;
        rising = rising && (k == 0 || watch.Progress[k] >= watch.Progress[k - 1]);
      }
      std::cout << stem << ".vti read directly: " << watch.Progress.size() << " progress events, "
                << within << " within the read:";
      for (const double p : watch.Progress)
      {
        std::cout << " " << p;
      }
      std::cout << "\n";
      vtkDataArray* whole = direct->GetOutput()->GetPointData()->GetArray("scalar");
      Check(whole && whole->GetNumberOfTuples() == scalar->GetNumberOfTuples() && within >= 1 &&
          rising && !watch.Progress.empty() && watch.Progress.back() == 1.0,
        stem + ".vti read on every thread: the reader's progress moves within the read");
      Watch aborted;
      vtkNew<vtkBrumeXMLImageDataReader> stopped;
      aborted.AbortAt = stopped;
      progress->SetClientData(&aborted);
      stopped->SetFileName((dir + "/" + stem + ".vti").c_str());
      stopped->AddObserver(vtkCommand::ProgressEvent, progress);
      const bool warnings = vtkObject::GetGlobalWarningDisplay();
      vtkObject::GlobalWarningDisplayOff();
      const int rc = stopped->GetExecutive()->Update();
      vtkObject::SetGlobalWarningDisplay(warnings);
      vtkDataArray* partial = stopped->GetOutput()->GetPointData()->GetArray("scalar");
      std::cout << stem << ".vti aborted within the read: " << (rc ? "updated" : "failed")
                << ", its array " << (partial ? "read" : "left out") << "\n";
      Check(!partial, stem + ".vti aborted within the read: its array is not given");
      // A byte of the volume's compressed blocks changed (three quarters
      // into the file: its appended data), in a copy: zlib's checksum fails.
      const std::string volumeFile = dir + "/" + stem + ".vti";
      std::string bytes;
      {
        std::ifstream in(volumeFile, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
      const std::size_t at = 3 * bytes.size() / 4;
      bytes[at] = static_cast<char>(bytes[at] == 'A' ? 'B' : 'A');
      std::ofstream(volumeFile, std::ios::binary | std::ios::trunc) << bytes;
      vtkNew<vtkBrumeSceneReader> corrupt;
      corrupt->SetFileName(scene.c_str());
      const bool display = vtkObject::GetGlobalWarningDisplay();
      vtkObject::GlobalWarningDisplayOff();
      const bool refused = corrupt->GetExecutive()->Update() == 0;
      vtkObject::SetGlobalWarningDisplay(display);
      std::cout << stem << ": a corrupt block " << (refused ? "refused" : "read") << "\n";
      Check(refused, stem + ".vti with a corrupt block: refused");
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// Every scene of `scenes` reads (its volume where `shared` has it, its
// medium's box from the grid's) and the particles of its light reach its
// medium: a measurement scene whose medium the light misses measures nothing.
int SharedScenes(const std::string& scenes, const std::string& shared)
{
  if (!std::filesystem::is_directory(shared))
  {
    std::cout << "no shared sample volumes: skipped\n";
    return EXIT_SUCCESS;
  }
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scenes))
  {
    if (entry.path().extension() != ".json")
    {
      continue;
    }
    const std::string name = entry.path().filename().string();
    vtkNew<vtkBrumeSceneReader> reader;
    reader->SetFileName(entry.path().string().c_str());
    const bool ok = reader->GetExecutive()->Update() == 1;
    Check(ok, name + " reads");
    if (!ok)
    {
      continue;
    }
    ++read;
    auto* collection =
      vtkPartitionedDataSetCollection::SafeDownCast(reader->GetOutputDataObject(0));
    const vtkIdType objects = collection ? collection->GetNumberOfPartitionedDataSets() : 0;
    const auto hits = Trace(reader);
    vtkDataArray* ids = hits->GetPointData()->GetArray(vtkBrumeHitConversion::ObjectIdName);
    // One medium, listed after the surfaces.
    vtkIdType inMedium = 0;
    for (vtkIdType i = 0; ids && i < ids->GetNumberOfTuples(); ++i)
    {
      inMedium += static_cast<vtkIdType>(ids->GetTuple1(i)) == objects - 1 ? 1 : 0;
    }
    std::cout << name << ": " << objects << " objects, " << hits->GetNumberOfPoints() << " hits, "
              << inMedium << " in the medium\n";
    Check(inMedium >= 100, name + ": the light reaches the medium");
  }
  Check(read >= 4, "the four shared volumes' scenes are there");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

int TestSceneFiles(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "roundtrip" && argc > 4)
  {
    return RoundTrip(argv[2], argv[3], argv[4]);
  }
  if (mode == "openvdb" && argc > 2)
  {
    return OpenVDB(argv[2], argc > 3 ? argv[3] : "");
  }
  if (mode == "meshes" && argc > 2)
  {
    return Meshes(argv[2]);
  }
  if (mode == "appended" && argc > 2)
  {
    return Appended(argv[2]);
  }
  if (mode == "shared" && argc > 3)
  {
    return SharedScenes(argv[2], argv[3]);
  }
  std::cerr << "usage: TestSceneFiles roundtrip DIR SCENE.json TF_SCENE.json | openvdb DIR "
               "[SHARED_VDB_DIR] | "
               "meshes DIR | appended DIR | shared SCENES SHARED_VDB_DIR\n";
  return EXIT_FAILURE;
}
