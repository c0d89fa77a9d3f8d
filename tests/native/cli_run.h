#pragma once
// Runs the native CLI (TVF_CLI_PATH) as a user would: its stdout, its stderr and its exit status.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

struct CliRun {
  int exitCode;
  std::string out, err;
};

#ifdef TVF_CLI_PATH
inline CliRun runTvf(const std::string& args) {
  // ctest runs tests in parallel processes: each call gets its own stderr file.
  static int calls = 0;
  namespace fs = std::filesystem;
  const fs::path errFile = fs::temp_directory_path() / ("tvf_cli_stderr_" + std::to_string(getpid()) + "_" +
                                                        std::to_string(calls++) + ".txt");
  const std::string command = std::string(TVF_CLI_PATH) + " " + args + " 2>" + errFile.string();
  CliRun r{-1, "", ""};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(errFile);
  r.err.assign(std::istreambuf_iterator<char>(in), {});
  fs::remove(errFile);
  return r;
}
#endif
