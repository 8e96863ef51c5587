// SPDX-License-Identifier: BSD-3-Clause
// VTK's XML readers as Brume::IO uses them (private to the module): each
// reads appended data whatever the expat it is linked with.
//
// Expat 2.6 (and Debian 12's security updates of 2.5.0, from 2.5.0-1+deb12u2)
// defer reparsing a token until more input arrives. VTK 9.2's
// vtkXMLDataParser hands expat the file up to the `_` that starts the
// appended data, then reads that data itself from the byte expat reached;
// with reparsing deferred, expat has not reached it, and a file of appended
// data (what VTK's and ParaView's writers give by default) fails to read
// ("not well-formed (invalid token)") or reads wrong. These readers parse
// with deferral switched off, as expat 2.5.0 parsed, where the expat linked
// at run time has XML_SetReparseDeferralEnabled(); an expat without it does
// not defer, and needs nothing.
#ifndef vtkBrumeXMLReaders_h
#define vtkBrumeXMLReaders_h

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <string>

/// vtkXMLDataParser with expat's reparse deferral switched off, which
/// also reads a whole compressed appended array on every thread.
class vtkBrumeXMLDataParser : public vtkXMLDataParser
{
public:
  static vtkBrumeXMLDataParser* New();
  vtkTypeMacro(vtkBrumeXMLDataParser, vtkXMLDataParser);

  /**
   * Reads all `numWords` words (`wordSize` bytes each) of the compressed
   * array at `offset` in the appended data of `fileName` (the file this
   * parser parsed), raw or base64, into `buffer`: its blocks decoded and
   * decompressed on vtkSMPTools' threads, each into its place, so the
   * values are those VTK's serial reading gives. 1: read; 0: not such an
   * array (uncompressed, of the other byte order, or of another size than
   * `numWords`), for VTK's reading; -1: an error, reported (the file holds
   * less than its header announces, or a block does not decompress to its
   * size; or the reader aborted: it reports its progress, in groups of
   * blocks, as VTK's reading does).
   */
  int ReadCompressedAppendedArray(
    const char* fileName, vtkTypeInt64 offset, void* buffer, size_t numWords, size_t wordSize);

protected:
  vtkBrumeXMLDataParser() = default;
  ~vtkBrumeXMLDataParser() override = default;
  int CreateParser() override;

private:
  vtkBrumeXMLDataParser(const vtkBrumeXMLDataParser&) = delete;
  void operator=(const vtkBrumeXMLDataParser&) = delete;
};

/// VTK XML's name of a type of array values (Float32, UInt8, ...), null for
/// others (vtkIdType, bits, strings), which VTK's reading converts.
const char* vtkBrumeXMLWordTypeName(int dataType);

/// A VTK XML reader (vtkXMLImageDataReader, ...) parsing with
/// vtkBrumeXMLDataParser.
template <class Reader>
class vtkBrumeXMLReader : public Reader
{
public:
  static vtkBrumeXMLReader* New()
  {
    auto* reader = new vtkBrumeXMLReader;
    reader->InitializeObjectBase();
    return reader;
  }
  vtkTemplateTypeMacro(vtkBrumeXMLReader, Reader);

protected:
  vtkBrumeXMLReader() = default;
  ~vtkBrumeXMLReader() override = default;
  void CreateXMLParser() override
  {
    if (this->XMLParser)
    {
      this->DestroyXMLParser();
    }
    this->XMLParser = vtkBrumeXMLDataParser::New();
    // What vtkXMLDataReader's own parser reports to: reading an array's
    // data moves the reader's progress, and aborting the reader stops it.
    this->XMLParser->AddObserver(vtkCommand::ProgressEvent, this->DataProgressObserver);
  }
  /// A whole array of a file's compressed appended data, of at least
  /// 1 MB, is read on every thread
  /// (vtkBrumeXMLDataParser::ReadCompressedAppendedArray); the rest as VTK reads it.
  int ReadArrayValues(vtkXMLDataElement* da, vtkIdType arrayIndex, vtkAbstractArray* array,
    vtkIdType startIndex, vtkIdType numValues,
    vtkXMLReader::FieldType type = vtkXMLReader::OTHER) override
  {
    auto* parser = vtkBrumeXMLDataParser::SafeDownCast(this->XMLParser);
    auto* data = vtkDataArray::FastDownCast(array);
    vtkTypeInt64 offset = 0;
    const char* format = da ? da->GetAttribute("format") : nullptr;
    const char* fileType = da ? da->GetAttribute("type") : nullptr;
    const char* arrayType = data ? vtkBrumeXMLWordTypeName(data->GetDataType()) : nullptr;
    if (parser && data && this->FileName && !this->ReadFromInputString && format &&
      std::string(format) == "appended" && fileType && arrayType &&
      std::string(fileType) == arrayType && da->GetScalarAttribute("offset", offset) &&
      arrayIndex == 0 && startIndex == 0 && numValues == data->GetNumberOfValues() &&
      static_cast<double>(numValues) * data->GetDataTypeSize() >= 1 << 20)
    {
      // As vtkXMLDataReader's reading does: the parser's progress counts.
      this->InReadData = 1;
      const int read =
        parser->ReadCompressedAppendedArray(this->FileName, offset, data->GetVoidPointer(0),
          static_cast<size_t>(numValues), static_cast<size_t>(data->GetDataTypeSize()));
      this->InReadData = 0;
      if (read != 0)
      {
        return read > 0 ? 1 : 0;
      }
    }
    return Reader::ReadArrayValues(da, arrayIndex, array, startIndex, numValues, type);
  }

private:
  vtkBrumeXMLReader(const vtkBrumeXMLReader&) = delete;
  void operator=(const vtkBrumeXMLReader&) = delete;
};

using vtkBrumeXMLImageDataReader = vtkBrumeXMLReader<vtkXMLImageDataReader>;
using vtkBrumeXMLPolyDataReader = vtkBrumeXMLReader<vtkXMLPolyDataReader>;
using vtkBrumeXMLUnstructuredGridReader = vtkBrumeXMLReader<vtkXMLUnstructuredGridReader>;

#endif
