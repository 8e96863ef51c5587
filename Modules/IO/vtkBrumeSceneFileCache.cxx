// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneFileCache.h"

#include <system_error>

bool vtkBrumeSceneFileCache::Stamp(
  const std::filesystem::path& file, std::filesystem::file_time_type& time, std::uintmax_t& size)
{
  std::error_code error;
  time = std::filesystem::last_write_time(file, error);
  if (error)
  {
    return false;
  }
  size = std::filesystem::file_size(file, error);
  return !error;
}

vtkDataObject* vtkBrumeSceneFileCache::Find(
  const std::filesystem::path& file, const std::string& kind)
{
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(file, error);
  auto it = this->Entries.find({ (error ? file : canonical).string(), kind });
  std::filesystem::file_time_type time;
  std::uintmax_t size = 0;
  if (it == this->Entries.end() || !Stamp(file, time, size) || time != it->second.Time ||
    size != it->second.Size)
  {
    return nullptr;
  }
  it->second.Used = true;
  return it->second.Data;
}

void vtkBrumeSceneFileCache::Keep(
  const std::filesystem::path& file, const std::string& kind, vtkDataObject* data)
{
  ++this->Reads;
  Entry entry;
  if (!data || !Stamp(file, entry.Time, entry.Size))
  {
    return;
  }
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(file, error);
  entry.Data = data;
  entry.Used = true;
  this->Entries[{ (error ? file : canonical).string(), kind }] = entry;
}

void vtkBrumeSceneFileCache::BeginParse()
{
  for (auto& entry : this->Entries)
  {
    entry.second.Used = false;
  }
}

void vtkBrumeSceneFileCache::EndParse()
{
  for (auto it = this->Entries.begin(); it != this->Entries.end();)
  {
    it = it->second.Used ? std::next(it) : this->Entries.erase(it);
  }
}
