// SPDX-License-Identifier: BSD-3-Clause
// Reading a float grid from an OpenVDB file, for code that links OpenVDB
// itself (the core's VdbDensity, the IO module's reader): one place for the
// checks every Brume use of a grid needs.
#ifndef brume_VdbGrid_h
#define brume_VdbGrid_h

#include <openvdb/openvdb.h>

#include <string>

namespace brume
{

/**
 * The float grid `gridName` of the file (empty: its first float grid), read
 * after CheckVdbFile; it must have an axis-aligned scale-and-translation
 * transform. Null, with the reason in `error`, otherwise. Only that grid's
 * data is read (the others' metadata decide which one).
 */
openvdb::FloatGrid::Ptr ReadVdbFloatGrid(
  const std::string& fileName, const std::string& gridName, std::string& error);

} // namespace brume

#endif
