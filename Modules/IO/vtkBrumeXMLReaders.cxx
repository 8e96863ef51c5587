// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeXMLReaders.h"

#include "vtkBase64Utilities.h"
#include "vtkDataCompressor.h"
#include "vtkInputStream.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"
#include "vtk_expat.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

vtkStandardNewMacro(vtkBrumeXMLDataParser);

namespace
{
using SetReparseDeferral = XML_Bool (*)(XML_Parser, XML_Bool);

// Looked up at run time, not linked: Brume built against an expat that
// declares it still runs with one that lacks it, and the other way round.
// It is looked up in the expat that VTK's parser calls (the library holding
// XML_ParserCreate()), not in the process's global scope, which does not
// hold it where Python or ParaView loaded Brume (RTLD_LOCAL).
SetReparseDeferral ReparseDeferralSetter()
{
  static const SetReparseDeferral setter = []() -> SetReparseDeferral
  {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&XML_ParserCreate), &info) || !info.dli_fname)
    {
      return nullptr;
    }
    // Already loaded (VTK's parser links it): this only takes a reference.
    void* expat = dlopen(info.dli_fname, RTLD_LAZY | RTLD_NOLOAD);
    return expat
      ? reinterpret_cast<SetReparseDeferral>(dlsym(expat, "XML_SetReparseDeferralEnabled"))
      : nullptr;
  }();
  return setter;
}
}

int vtkBrumeXMLDataParser::CreateParser()
{
  if (!this->Superclass::CreateParser())
  {
    return 0;
  }
  if (const SetReparseDeferral setter = ReparseDeferralSetter())
  {
    setter(static_cast<XML_Parser>(this->Parser), XML_FALSE);
  }
  return 1;
}

const char* vtkBrumeXMLWordTypeName(int dataType)
{
  switch (dataType)
  {
    case VTK_FLOAT:
      return "Float32";
    case VTK_DOUBLE:
      return "Float64";
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      return "Int8";
    case VTK_UNSIGNED_CHAR:
      return "UInt8";
    case VTK_SHORT:
      return "Int16";
    case VTK_UNSIGNED_SHORT:
      return "UInt16";
    case VTK_INT:
      return "Int32";
    case VTK_UNSIGNED_INT:
      return "UInt32";
    case VTK_LONG_LONG:
      return "Int64";
    case VTK_UNSIGNED_LONG_LONG:
      return "UInt64";
    default:
      return nullptr;
  }
}

namespace
{
// A file read by position from any thread (pread), closed with the object.
struct PositionedFile
{
  explicit PositionedFile(const char* name)
    : Descriptor(::open(name, O_RDONLY | O_CLOEXEC))
  {
    struct stat info
    {
    };
    this->Size = this->Descriptor >= 0 && ::fstat(this->Descriptor, &info) == 0
      ? static_cast<vtkTypeInt64>(info.st_size)
      : -1;
  }
  ~PositionedFile()
  {
    if (this->Descriptor >= 0)
    {
      ::close(this->Descriptor);
    }
  }
  PositionedFile(const PositionedFile&) = delete;
  PositionedFile& operator=(const PositionedFile&) = delete;
  // `n` bytes at `at` (all of them, or false).
  bool Read(vtkTypeInt64 at, size_t n, unsigned char* out) const
  {
    while (n > 0)
    {
      const ssize_t got = ::pread(this->Descriptor, out, n, static_cast<off_t>(at));
      if (got <= 0)
      {
        return false;
      }
      out += got;
      at += got;
      n -= static_cast<size_t>(got);
    }
    return true;
  }
  int Descriptor;
  vtkTypeInt64 Size = -1;
};

// Base64's characters for `bytes` bytes, padded: 4 per 3.
vtkTypeInt64 EncodedLength(vtkTypeUInt64 bytes)
{
  return static_cast<vtkTypeInt64>(4 * ((bytes + 2) / 3));
}
}

int vtkBrumeXMLDataParser::ReadCompressedAppendedArray(
  const char* fileName, vtkTypeInt64 offset, void* buffer, size_t numWords, size_t wordSize)
{
#ifdef VTK_WORDS_BIGENDIAN
  const bool native = this->ByteOrder == vtkXMLDataParser::BigEndian;
#else
  const bool native = this->ByteOrder == vtkXMLDataParser::LittleEndian;
#endif
  vtkDataCompressor* compressor = this->Compressor;
  if (!compressor || !native || !fileName || this->AppendedDataPosition <= 0 ||
    !this->AppendedDataStream || numWords == 0 || wordSize == 0)
  {
    return 0;
  }
  const bool base64 = this->AppendedDataStream->IsA("vtkBase64InputStream") != 0;
  const PositionedFile file(fileName);
  if (file.Size < 0)
  {
    return 0; // VTK's reading says why
  }
  auto fail = [&](const std::string& why)
  {
    vtkErrorMacro("Cannot read '" << fileName << "': the compressed array at appended offset "
                                  << offset << " " << why << ".");
    return -1;
  };
  // The header: blocks, their size, the last one's, then each block's
  // compressed size, words of 4 or 8 bytes (header_type); base64 encodes
  // it on its own, before the blocks.
  const size_t word = this->HeaderType == 64 ? 8 : 4;
  const vtkTypeInt64 start = this->AppendedDataPosition + offset;
  auto readHeader = [&](size_t words, std::vector<vtkTypeUInt64>& out)
  {
    const size_t bytes = words * word;
    std::vector<unsigned char> raw(bytes + 3);
    if (base64)
    {
      std::vector<unsigned char> text(static_cast<size_t>(EncodedLength(bytes)));
      if (!file.Read(start, text.size(), text.data()) ||
        vtkBase64Utilities::DecodeSafely(text.data(), text.size(), raw.data(), raw.size()) < bytes)
      {
        return false;
      }
    }
    else if (!file.Read(start, bytes, raw.data()))
    {
      return false;
    }
    out.resize(words);
    for (size_t w = 0; w < words; ++w)
    {
      if (word == 8)
      {
        vtkTypeUInt64 v;
        std::memcpy(&v, raw.data() + 8 * w, 8);
        out[w] = v;
      }
      else
      {
        vtkTypeUInt32 v;
        std::memcpy(&v, raw.data() + 4 * w, 4);
        out[w] = v;
      }
    }
    return true;
  };
  std::vector<vtkTypeUInt64> header;
  if (!readHeader(3, header))
  {
    return fail("has no compression header within the file");
  }
  const vtkTypeUInt64 blocks = header[0], blockSize = header[1], last = header[2];
  // Of another size than the array, or a header no file could hold: VTK's
  // reading decides. Checked without overflow, so that every block lies
  // within the array.
  const vtkTypeUInt64 arrayBytes = static_cast<vtkTypeUInt64>(numWords) * wordSize;
  if (blocks == 0 || blockSize == 0 || blockSize > arrayBytes || last > blockSize ||
    blocks - 1 > arrayBytes / blockSize || blocks > static_cast<vtkTypeUInt64>(file.Size) / word ||
    (blocks - 1) * blockSize + (last != 0 ? last : blockSize) != arrayBytes)
  {
    return 0;
  }
  if (!readHeader(3 + static_cast<size_t>(blocks), header))
  {
    return fail("has a compression header longer than the file");
  }
  // Where each block starts among the compressed bytes.
  std::vector<vtkTypeUInt64> begins(static_cast<size_t>(blocks) + 1, 0);
  for (size_t b = 0; b < blocks; ++b)
  {
    begins[b + 1] = begins[b] + header[3 + b];
  }
  const vtkTypeInt64 headerLength =
    base64 ? EncodedLength((3 + blocks) * word) : static_cast<vtkTypeInt64>((3 + blocks) * word);
  const vtkTypeInt64 dataStart = start + headerLength;
  const vtkTypeUInt64 compressed = begins.back();
  if (compressed > static_cast<vtkTypeUInt64>(file.Size) ||
    dataStart + (base64 ? EncodedLength(compressed) : static_cast<vtkTypeInt64>(compressed)) >
      file.Size)
  {
    return fail(
      "announces " + std::to_string(compressed) + " compressed bytes, more than the file holds");
  }
  // Groups of 256 blocks (8 MB of VTK's default blocks), each read,
  // decoded and decompressed by one thread into its place.
  constexpr size_t Group = 256;
  const size_t groups = static_cast<size_t>((blocks + Group - 1) / Group);
  std::atomic<vtkTypeInt64> badBlock{ -1 };
  auto* out = static_cast<unsigned char*>(buffer);
  // Read in steps of a few groups a thread, the progress reported (and an
  // abort heeded) between them, on this thread.
  const size_t step = std::max<size_t>(
    2 * static_cast<size_t>(std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads())),
    (groups + 19) / 20);
  this->UpdateProgress(0.f);
  for (size_t done = 0; done < groups && badBlock.load() < 0; done += step)
  {
    if (this->GetAbort())
    {
      return -1;
    }
    vtkSMPTools::For(static_cast<vtkIdType>(done),
      static_cast<vtkIdType>(std::min(groups, done + step)),
      [&](vtkIdType first, vtkIdType end)
      {
        std::vector<unsigned char> bytes, text;
        for (vtkIdType g = first; g < end && badBlock.load() < 0; ++g)
        {
          const size_t b0 = static_cast<size_t>(g) * Group;
          const size_t b1 = std::min(static_cast<size_t>(blocks), b0 + Group);
          const vtkTypeUInt64 from = begins[b0], to = begins[b1];
          // The group's bytes, from `from` (base64: from the group of four
          // characters holding it, `skip` bytes before it).
          size_t skip = 0;
          bool read = false;
          if (base64)
          {
            const vtkTypeUInt64 firstTriplet = from / 3, endTriplet = (to + 2) / 3;
            skip = static_cast<size_t>(from - 3 * firstTriplet);
            text.resize(static_cast<size_t>(4 * (endTriplet - firstTriplet)));
            bytes.resize(static_cast<size_t>(3 * (endTriplet - firstTriplet)));
            read = file.Read(dataStart + static_cast<vtkTypeInt64>(4 * firstTriplet), text.size(),
                     text.data()) &&
              vtkBase64Utilities::DecodeSafely(text.data(), text.size(), bytes.data(),
                bytes.size()) >= skip + static_cast<size_t>(to - from);
          }
          else
          {
            bytes.resize(static_cast<size_t>(to - from));
            read =
              file.Read(dataStart + static_cast<vtkTypeInt64>(from), bytes.size(), bytes.data());
          }
          for (size_t b = b0; b < b1; ++b)
          {
            const size_t size = b + 1 == blocks && last != 0 ? static_cast<size_t>(last)
                                                             : static_cast<size_t>(blockSize);
            const bool ok = read &&
              compressor->Uncompress(bytes.data() + skip + (begins[b] - from),
                static_cast<size_t>(header[3 + b]), out + b * blockSize, size) == size;
            if (!ok)
            {
              vtkTypeInt64 known = badBlock.load();
              while ((known < 0 || static_cast<vtkTypeInt64>(b) < known) &&
                !badBlock.compare_exchange_weak(known, static_cast<vtkTypeInt64>(b)))
              {
              }
              break;
            }
          }
        }
      });
    this->UpdateProgress(
      static_cast<float>(std::min(groups, done + step)) / static_cast<float>(groups));
  }
  if (badBlock.load() >= 0)
  {
    return fail("has a block (" + std::to_string(badBlock.load()) + " of " +
      std::to_string(blocks) + ") that does not decompress to its size");
  }
  return 1;
}
