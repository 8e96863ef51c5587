// SPDX-License-Identifier: BSD-3-Clause
// Bad-input tests: run an algorithm and check that it fails with an error
// that says what is wrong.
#ifndef BrumeExpectFailure_h
#define BrumeExpectFailure_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"

#include <iostream>
#include <string>

/// The last error an algorithm reported (an ErrorEvent observer).
struct BrumeErrorCatcher
{
  std::string Last;
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    static_cast<BrumeErrorCatcher*>(clientData)->Last = static_cast<const char*>(callData);
  }
};

/**
 * Updates `algorithm` and checks that it fails with an error mentioning
 * `expected`; prints the error (or, when not, what happened instead).
 */
inline bool ExpectFailure(
  const std::string& what, vtkAlgorithm* algorithm, const std::string& expected)
{
  BrumeErrorCatcher catcher;
  vtkNew<vtkCallbackCommand> command;
  command->SetCallback(BrumeErrorCatcher::Callback);
  command->SetClientData(&catcher);
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, command);
  const int ok = algorithm->GetExecutive()->Update();
  algorithm->RemoveObserver(tag);
  if (ok || catcher.Last.find(expected) == std::string::npos)
  {
    std::cerr << what << ": expected a failure mentioning '" << expected << "', got "
              << (ok ? "success" : "failure") << " with error '" << catcher.Last << "'\n";
    return false;
  }
  std::cout << what << ": " << catcher.Last.substr(catcher.Last.find('\n') + 1);
  return true;
}

#endif
