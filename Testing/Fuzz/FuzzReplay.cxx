// SPDX-License-Identifier: BSD-3-Clause
// Runs a fuzz target's LLVMFuzzerTestOneInput over a seed corpus once, as
// libFuzzer does with -runs=0, in a build that has no libFuzzer (GCC, the
// sanitizers' build of scripts/sanitize.sh): each input, cut to --max-len
// bytes, within --timeout seconds, the process's resident memory within
// --rss-mb; the first input that crashes, runs over or grows beyond them
// fails the run, named. With --format-byte, each input is preceded by the
// byte FuzzSceneFiles reads as its format, from the file's extension.
//   FuzzReplay[Target] [--format-byte] [--max-len N] [--timeout S] [--rss-mb M] FILE...
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{
// The input being run, for the alarm's message (a fixed buffer: the handler
// may only write what is already there).
char Current[4096] = "";

void OnAlarm(int)
{
  const char head[] = "FuzzReplay: timeout on ";
  ssize_t ignored = ::write(2, head, sizeof(head) - 1);
  ignored = ::write(2, Current, std::strlen(Current));
  ignored = ::write(2, "\n", 1);
  static_cast<void>(ignored);
  std::_Exit(1);
}

// FuzzSceneFiles' first byte: 0 vti, 1 ply, 2 obj, 3 stl, 4 vtp, 5 vtu.
int FormatByte(const std::string& file)
{
  static const char* const formats[] = { "vti", "ply", "obj", "stl", "vtp", "vtu" };
  const std::size_t dot = file.rfind('.');
  const std::string extension = dot == std::string::npos ? "" : file.substr(dot + 1);
  for (int b = 0; b < 6; ++b)
  {
    if (extension == formats[b])
    {
      return b;
    }
  }
  return -1;
}

int Usage(const char* name)
{
  std::fprintf(
    stderr, "usage: %s [--format-byte] [--max-len N] [--timeout S] [--rss-mb M] FILE...\n", name);
  return 2;
}
}

int main(int argc, char* argv[])
{
  bool formatByte = false;
  long maxLen = 65536, timeout = 10, rssMb = 2048;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    long* value = arg == "--max-len" ? &maxLen
      : arg == "--timeout"           ? &timeout
      : arg == "--rss-mb"            ? &rssMb
                                     : nullptr;
    if (arg == "--format-byte")
    {
      formatByte = true;
    }
    else if (value)
    {
      char* end = nullptr;
      if (i + 1 == argc || (*value = std::strtol(argv[++i], &end, 10), *end != '\0') || *value <= 0)
      {
        return Usage(argv[0]);
      }
    }
    else if (arg.rfind("--", 0) == 0)
    {
      return Usage(argv[0]);
    }
    else
    {
      files.push_back(arg);
    }
  }
  if (files.empty())
  {
    return Usage(argv[0]);
  }
  std::signal(SIGALRM, OnAlarm);
  for (const std::string& file : files)
  {
    std::ifstream in(file, std::ios::binary);
    if (!in)
    {
      std::fprintf(stderr, "FuzzReplay: cannot read %s\n", file.c_str());
      return 1;
    }
    std::vector<std::uint8_t> data;
    if (formatByte)
    {
      const int b = FormatByte(file);
      if (b < 0)
      {
        std::fprintf(stderr, "FuzzReplay: %s: no format byte for its extension\n", file.c_str());
        return 1;
      }
      data.push_back(static_cast<std::uint8_t>(b));
    }
    data.insert(data.end(), std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (data.size() > static_cast<std::size_t>(maxLen))
    {
      data.resize(static_cast<std::size_t>(maxLen));
    }
    std::snprintf(Current, sizeof(Current), "%s", file.c_str());
    ::alarm(static_cast<unsigned>(timeout));
    LLVMFuzzerTestOneInput(data.data(), data.size());
    ::alarm(0);
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    if (usage.ru_maxrss / 1024 > rssMb) // ru_maxrss is in kB on Linux
    {
      std::fprintf(stderr, "FuzzReplay: %s took the process to %ld MB (limit %ld MB)\n",
        file.c_str(), usage.ru_maxrss / 1024, rssMb);
      return 1;
    }
  }
  std::printf("FuzzReplay: %zu inputs\n", files.size());
  return 0;
}
