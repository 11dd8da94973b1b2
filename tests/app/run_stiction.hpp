// Runs the built `stiction` binary as a user would, in a scratch directory.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace stiction::testing {

struct Outcome {
  int code = -1;
  std::string out;  // stdout and stderr together
};

// A fresh empty directory per test and process.
inline std::filesystem::path scratch_dir(const std::string& prefix, const std::string& name) {
  std::string leaf = prefix;
  leaf += name + "_" + std::to_string(::getpid());
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / leaf;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string shell_quote(const std::string& s) {
  std::string q(1, '\'');
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline Outcome run_stiction(const std::vector<std::string>& args,
                            const std::filesystem::path& cwd) {
  std::string command = "cd ";
  command += shell_quote(cwd.string()) + " && " + shell_quote(STICTION_BINARY);
  for (const auto& a : args) {
    command += ' ';
    command += shell_quote(a);
  }
  command += " 2>&1";
  Outcome o;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) o.out.append(buffer, n);
  const int status = ::pclose(pipe);
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

}  // namespace stiction::testing
