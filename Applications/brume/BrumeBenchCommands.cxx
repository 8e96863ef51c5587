// SPDX-License-Identifier: BSD-3-Clause
// `brume bench`: `brume render` and `brume view` timed as whole processes.
#include "BrumeBench.h"

#include "vtkBrumeRenderWindowSelection.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace BrumeBench
{
// The environment of the commands the bench starts: its own, without what
// tells a process that mpirun started it (each command is one process).
std::vector<std::string> ChildEnvironment()
{
  std::vector<std::string> variables;
  for (char** v = environ; *v; ++v)
  {
    const std::string variable = *v;
    bool launcher = false;
    for (const char* prefix : { "OMPI_", "PMI_", "PMIX_", "HYDRA_", "MPIR_" })
    {
      launcher = launcher || variable.compare(0, std::strlen(prefix), prefix) == 0;
    }
    if (!launcher)
    {
      variables.push_back(variable);
    }
  }
  return variables;
}

// One `brume` command (this executable) as a new process, from its start
// to its exit: the wall seconds, or -1 (said) when it fails. With `line`
// not empty, the seconds until it printed a line beginning so instead.
// (posix_spawn rather than vtksys::Process: the child's environment must
// leave out the MPI launcher's variables, which vtksys cannot set.)
double TimeCommand(const std::vector<std::string>& arguments, const std::string& line = {})
{
  // /proc/self/exe itself: the running executable even if its file was
  // replaced by a rebuild meanwhile.
  const char* self = "/proc/self/exe";
  std::vector<std::string> words{ "brume" };
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<std::string> variables = ChildEnvironment();
  // The null-terminated arrays posix_spawn takes, over the strings above.
  auto pointers = [](std::vector<std::string>& strings)
  {
    std::vector<char*> p;
    for (std::string& s : strings)
    {
      p.push_back(s.data());
    }
    p.push_back(nullptr);
    return p;
  };
  std::vector<char*> argv = pointers(words), envp = pointers(variables);
  int out[2];
  if (pipe2(out, O_CLOEXEC) != 0)
  {
    std::perror("brume bench: pipe");
    return -1.0;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO); // clears close-on-exec
  pid_t child = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = posix_spawn(&child, self, &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  if (spawned != 0)
  {
    close(out[0]);
    std::fprintf(stderr, "brume bench: cannot start %s: %s\n", self, std::strerror(spawned));
    return -1.0;
  }
  // Its output, line by line (read to the end, so that it never blocks).
  double seconds = -1.0;
  std::string text, pending;
  char buffer[4096];
  for (ssize_t n; (n = read(out[0], buffer, sizeof(buffer))) != 0;)
  {
    if (n < 0)
    {
      if (errno == EINTR)
      {
        continue;
      }
      break;
    }
    pending.append(buffer, static_cast<std::size_t>(n));
    for (std::size_t end; (end = pending.find('\n')) != std::string::npos;)
    {
      if (!line.empty() && seconds < 0.0 && pending.compare(0, line.size(), line) == 0)
      {
        seconds = Seconds(start);
      }
      text += pending.substr(0, end + 1);
      pending.erase(0, end + 1);
    }
  }
  close(out[0]);
  int status = 0;
  pid_t waited = 0;
  while ((waited = waitpid(child, &status, 0)) < 0 && errno == EINTR)
  {
  }
  if (line.empty())
  {
    seconds = Seconds(start);
  }
  if (waited != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || seconds < 0.0)
  {
    std::fprintf(stderr, "brume bench: 'brume %s' failed%s:\n%s", words[1].c_str(),
      seconds < 0.0 && !line.empty() ? (" before printing '" + line + "'").c_str() : "",
      text.c_str());
    return -1.0;
  }
  return seconds;
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Whole commands as a user runs them, each a new process (start-up, scene,
// tracing, reconstruction, frame): `brume render -o FILE.png` to its exit,
// and `brume view` to its first image on screen; medians of three.
bool BenchWholeCommands(const BenchOptions& options, Report& report)
{
  // Both commands render: skipped, as the frames are, without a window.
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    std::printf("whole commands     skipped: %s\n", vtkBrumeRenderWindowSelection::GetLastError());
    return true;
  }
  // A directory of its own for the image (mkdtemp: made new, private).
  std::error_code error;
  std::filesystem::path temporary = std::filesystem::temp_directory_path(error);
  if (error)
  {
    temporary = "/tmp";
  }
  std::string name = (temporary / "brume-bench-XXXXXX").string();
  if (!mkdtemp(name.data()))
  {
    std::fprintf(
      stderr, "brume bench: cannot make a directory %s: %s\n", name.c_str(), std::strerror(errno));
    return false;
  }
  const std::filesystem::path directory = name;
  // The same budget, and the window this bench renders in.
  const std::vector<std::string> budget{ "--particles", std::to_string(*options.Particles),
    "--seed", std::to_string(options.Seed), "--window",
    vtkBrumeRenderWindowSelection::GetInstalled() };
  std::vector<std::string> render{ "render", "-o", (directory / "bench.png").string() };
  std::vector<std::string> view{ "view", "--orbit", "1" };
  render.insert(render.end(), budget.begin(), budget.end());
  view.insert(view.end(), budget.begin(), budget.end());
  std::vector<double> renders, views;
  for (int run = 0; run < 3; ++run)
  {
    renders.push_back(TimeCommand(render));
    views.push_back(TimeCommand(view, "first image:"));
    if (renders.back() < 0.0 || views.back() < 0.0)
    {
      std::filesystem::remove_all(directory, error);
      return false;
    }
  }
  std::filesystem::remove_all(directory, error);
  const double whole = Median(renders), first = Median(views);
  std::printf("whole commands     %8.3f s  brume render -o FILE.png, process start to file "
              "written; %.3f s brume view to its first image (medians of 3)\n",
    whole, first);
  report.Add("whole_command", whole, "s", "<= 1.0",
    "brume render -o FILE.png, process start to exit, 512x512, median of 3");
  report.Add("viewer_first_image", first, "s", "",
    "brume view, process start to its first image, 512x512, median of 3");
  return true;
}
}
