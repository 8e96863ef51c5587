// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeOutputWindow.h"

#include "vtkBrumeQuotes.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include <cstdlib>
#include <iostream>
#include <string>

vtkStandardNewMacro(BrumeOutputWindow);

void BrumeOutputWindow::Install()
{
  const char* keep = std::getenv("BRUME_VTK_MESSAGES");
  if (keep && *keep && std::string(keep) != "0")
  {
    return;
  }
  vtkNew<BrumeOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
  // VTK's logger would print every message a second time, with the
  // pipeline's reports: this window says what is wrong.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

std::string BrumeOutputWindow::Message(const char* text)
{
  std::string s = text ? text : "";
  if (s.find("returned failure for request") != std::string::npos)
  {
    return {};
  }
  // Drop the "ERROR: In FILE, line N" line, then the "CLASS (ADDRESS): "
  // prefix of the message.
  if (s.rfind("ERROR: In ", 0) == 0 || s.rfind("Warning: In ", 0) == 0 ||
    s.rfind("Generic Warning: In ", 0) == 0)
  {
    const std::size_t eol = s.find('\n');
    s = eol == std::string::npos ? std::string() : s.substr(eol + 1);
  }
  const std::size_t paren = s.find(" (0x");
  const std::size_t colon = paren == std::string::npos ? paren : s.find("): ", paren);
  if (colon != std::string::npos && s.find('\n') > colon)
  {
    s = s.substr(colon + 3);
  }
  while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
  {
    s.pop_back();
  }
  for (char& c : s)
  {
    c = c == '\n' ? ' ' : c;
  }
  // Whatever module said it: at most about 80 characters of any input.
  return vtkBrumeBoundQuotes(s);
}

void BrumeOutputWindow::DisplayErrorText(const char* text)
{
  const std::string message = Message(text);
  if (!message.empty())
  {
    std::cerr << "brume: " << message << "\n";
  }
}

void BrumeOutputWindow::DisplayWarningText(const char* text)
{
  const std::string message = Message(text);
  if (!message.empty())
  {
    std::cerr << "brume: warning: " << message << "\n";
  }
}

void BrumeOutputWindow::DisplayGenericWarningText(const char* text)
{
  this->DisplayWarningText(text);
}
