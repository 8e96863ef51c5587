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

#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLUnstructuredGridReader.h"

/// vtkXMLDataParser with expat's reparse deferral switched off.
class vtkBrumeXMLDataParser : public vtkXMLDataParser
{
public:
  static vtkBrumeXMLDataParser* New();
  vtkTypeMacro(vtkBrumeXMLDataParser, vtkXMLDataParser);

protected:
  vtkBrumeXMLDataParser() = default;
  ~vtkBrumeXMLDataParser() override = default;
  int CreateParser() override;

private:
  vtkBrumeXMLDataParser(const vtkBrumeXMLDataParser&) = delete;
  void operator=(const vtkBrumeXMLDataParser&) = delete;
};

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
  }

private:
  vtkBrumeXMLReader(const vtkBrumeXMLReader&) = delete;
  void operator=(const vtkBrumeXMLReader&) = delete;
};

using vtkBrumeXMLImageDataReader = vtkBrumeXMLReader<vtkXMLImageDataReader>;
using vtkBrumeXMLPolyDataReader = vtkBrumeXMLReader<vtkXMLPolyDataReader>;
using vtkBrumeXMLUnstructuredGridReader = vtkBrumeXMLReader<vtkXMLUnstructuredGridReader>;

#endif
