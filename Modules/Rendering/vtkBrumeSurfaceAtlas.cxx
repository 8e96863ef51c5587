// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSurfaceAtlas.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace vtkBrumeSceneActorsInternals
{
namespace
{
vtkFloatArray* Texels(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
}

// A member's slot: its texture's size and one texel on every side.
std::array<int, 2> SlotSize(const AtlasMember& member)
{
  const int* dims = member.Image->GetDimensions();
  return { dims[0] + 2, dims[1] + 2 };
}
}

bool SurfaceAtlas::Accepts(vtkImageData* image, vtkPolyData* surface)
{
  if (!image || !surface || !surface->GetPoints())
  {
    return false;
  }
  const int* dims = image->GetDimensions();
  vtkFloatArray* texels = Texels(image);
  if (dims[2] != 1 || dims[0] < 1 || dims[1] < 1 || dims[0] > MaxSide - 2 ||
    dims[1] > MaxSide - 2 || !texels || texels->GetNumberOfComponents() != 3 ||
    texels->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
  {
    return false;
  }
  vtkDataArray* tcoords = surface->GetPointData()->GetTCoords();
  return surface->GetNumberOfVerts() == 0 && surface->GetNumberOfLines() == 0 &&
    surface->GetNumberOfStrips() == 0 && tcoords && tcoords->GetNumberOfComponents() == 2 &&
    tcoords->GetNumberOfTuples() == surface->GetNumberOfPoints();
}

std::vector<SurfaceAtlas> SurfaceAtlas::Pack(std::vector<AtlasMember> members)
{
  std::vector<SurfaceAtlas> atlases;
  if (members.empty())
  {
    return atlases;
  }
  // Shelves, tallest slots first: each shelf is as tall as its first slot.
  std::stable_sort(members.begin(), members.end(),
    [](const AtlasMember& a, const AtlasMember& b)
    {
      const int ha = SlotSize(a)[1];
      const int hb = SlotSize(b)[1];
      return ha != hb ? ha > hb : a.Index < b.Index;
    });
  double area = 0.0;
  int widest = 0;
  for (const AtlasMember& m : members)
  {
    const auto slot = SlotSize(m);
    area += static_cast<double>(slot[0]) * slot[1];
    widest = std::max(widest, slot[0]);
  }
  // About square: the smallest power of two whose square holds the slots.
  int width = 1;
  while (static_cast<double>(width) * width < area && width < MaxSide)
  {
    width *= 2;
  }
  width = std::min(MaxSide, std::max(width, widest));

  SurfaceAtlas atlas;
  int x = 0;
  int y = 0;
  int shelf = 0;
  auto finish = [&]()
  {
    atlas.Width = width;
    atlas.Height = y + shelf;
    atlas.Build();
    atlases.push_back(std::move(atlas));
    atlas = SurfaceAtlas();
    x = y = shelf = 0;
  };
  for (AtlasMember& m : members)
  {
    const auto slot = SlotSize(m);
    if (x + slot[0] > width)
    {
      y += shelf;
      x = 0;
      shelf = 0;
    }
    if (y + slot[1] > MaxSide)
    {
      finish();
    }
    m.X = x;
    m.Y = y;
    x += slot[0];
    shelf = std::max(shelf, slot[1]);
    atlas.Members.push_back(std::move(m));
  }
  finish();
  return atlases;
}

void SurfaceAtlas::CopyTexels(const AtlasMember& member)
{
  const int* dims = member.Image->GetDimensions();
  const int w = dims[0];
  const int h = dims[1];
  const float* source = Texels(member.Image)->GetPointer(0);
  float* atlas = Texels(this->Image)->GetPointer(0);
  for (int row = 0; row < h + 2; ++row)
  {
    const float* from = source + 3 * static_cast<std::size_t>(std::min(h - 1, std::max(0, row - 1))) * w;
    float* to = atlas + 3 * (static_cast<std::size_t>(member.Y + row) * this->Width + member.X);
    std::memcpy(to, from, 3 * sizeof(float));
    std::memcpy(to + 3, from, 3 * sizeof(float) * w);
    std::memcpy(to + 3 * (w + 1), from + 3 * (w - 1), 3 * sizeof(float));
  }
}

void SurfaceAtlas::SetTexels(std::size_t k, vtkImageData* image)
{
  this->Members[k].Image = image;
  this->CopyTexels(this->Members[k]);
  Texels(this->Image)->Modified();
  this->Image->Modified();
}

void SurfaceAtlas::Build()
{
  // The geometry in the input's order, whatever the packing's.
  std::sort(this->Members.begin(), this->Members.end(),
    [](const AtlasMember& a, const AtlasMember& b) { return a.Index < b.Index; });
  const auto n = static_cast<vtkIdType>(this->Members.size());

  this->Image = vtkSmartPointer<vtkImageData>::New();
  this->Image->SetDimensions(this->Width, this->Height, 1);
  this->Image->SetSpacing(1.0 / this->Width, 1.0 / this->Height, 1.0);
  this->Image->SetOrigin(0.5 / this->Width, 0.5 / this->Height, 0.0);
  vtkNew<vtkFloatArray> texels;
  texels->SetName(Texels(this->Members[0].Image)->GetName());
  texels->SetNumberOfComponents(3);
  texels->SetNumberOfTuples(static_cast<vtkIdType>(this->Width) * this->Height);
  texels->FillValue(0.0f);
  this->Image->GetPointData()->SetScalars(texels);

  // Where each member's points, polygons and connectivity start.
  std::vector<vtkIdType> points(n + 1, 0);
  std::vector<vtkIdType> cells(n + 1, 0);
  std::vector<vtkIdType> ids(n + 1, 0);
  bool doubles = false;
  for (vtkIdType k = 0; k < n; ++k)
  {
    vtkPolyData* surface = this->Members[k].Surface;
    points[k + 1] = points[k] + surface->GetNumberOfPoints();
    cells[k + 1] = cells[k] + surface->GetPolys()->GetNumberOfCells();
    ids[k + 1] = ids[k] + surface->GetPolys()->GetNumberOfConnectivityIds();
    doubles = doubles || surface->GetPoints()->GetDataType() == VTK_DOUBLE;
  }
  vtkNew<vtkPoints> xyz;
  xyz->SetDataType(doubles ? VTK_DOUBLE : VTK_FLOAT);
  xyz->SetNumberOfPoints(points[n]);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName(this->Members[0].Surface->GetPointData()->GetTCoords()->GetName());
  tcoords->SetNumberOfComponents(2);
  tcoords->SetNumberOfTuples(points[n]);
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(cells[n] + 1);
  offsets->SetValue(cells[n], ids[n]);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(ids[n]);

  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkNew<vtkIdList> scratch;
      for (vtkIdType k = begin; k < end; ++k)
      {
        const AtlasMember& m = this->Members[k];
        this->CopyTexels(m);
        const int* dims = m.Image->GetDimensions();
        vtkPolyData* surface = m.Surface;
        vtkDataArray* uv = surface->GetPointData()->GetTCoords();
        for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
        {
          double at[3];
          surface->GetPoint(p, at);
          xyz->GetData()->SetTuple(points[k] + p, at);
          // The texture's [0, 1] spans its texels inside the slot's border.
          tcoords->SetTypedComponent(points[k] + p, 0,
            static_cast<float>((m.X + 1 + uv->GetComponent(p, 0) * dims[0]) / this->Width));
          tcoords->SetTypedComponent(points[k] + p, 1,
            static_cast<float>((m.Y + 1 + uv->GetComponent(p, 1) * dims[1]) / this->Height));
        }
        vtkCellArray* polys = surface->GetPolys();
        vtkIdType at = ids[k];
        for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
        {
          vtkIdType size;
          const vtkIdType* corners;
          polys->GetCellAtId(c, size, corners, scratch);
          offsets->SetValue(cells[k] + c, at);
          for (vtkIdType i = 0; i < size; ++i)
          {
            connectivity->SetValue(at++, points[k] + corners[i]);
          }
        }
      }
    });

  this->Geometry = vtkSmartPointer<vtkPolyData>::New();
  this->Geometry->SetPoints(xyz);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  this->Geometry->SetPolys(polys);
  this->Geometry->GetPointData()->SetTCoords(tcoords);
}
}
