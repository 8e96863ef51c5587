// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkBrumeQuotes.h
 * @brief   messages that quote at most about 80 characters of an input
 *
 * A malformed input can hold a 100 MB key, name or string; an error that
 * quotes it whole copies it to stderr. vtkBrumeBoundQuotes() shortens every
 * '...'-quoted part of a message longer than `most` characters to its first
 * and last characters around an ellipsis (a file's path keeps its name).
 */
#ifndef vtkBrumeQuotes_h
#define vtkBrumeQuotes_h

#include "vtkBrumeDataModelModule.h" // For export macro

#include <cstddef>
#include <string>

/// `message` with every quoted part over `most` characters shortened.
VTKBRUMEDATAMODEL_EXPORT std::string vtkBrumeBoundQuotes(
  const std::string& message, std::size_t most = 80);

#endif
