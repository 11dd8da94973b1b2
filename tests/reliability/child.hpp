// A `stiction` child process that a test can signal: started with posix_spawn in a given
// directory, stdout and stderr to files, waited for with a bound (a hang fails the test
// instead of blocking the suite).
#pragma once

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

extern char** environ;

namespace stiction::testing {

// The limits below are hang guards, never timing assertions. Under ASan the test and the
// child it starts are both instrumented and run 3-10 times slower (a sweep resumed in CI
// took over 60 s), so every guard is stretched there.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kHangGuardScale = 5.0;
#else
inline constexpr double kHangGuardScale = 1.0;
#endif

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every regular file under `dir` with its content, by relative name: what a test compares
// before and after a command that must leave files alone.
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) {
      files[std::filesystem::relative(e.path(), dir).generic_string()] = read_text(e.path());
    }
  }
  return files;
}

class Child {
 public:
  Child(const std::vector<std::string>& args, const std::filesystem::path& cwd, std::string log_name = "child")
      : out_(cwd / (log_name + ".stdout")), err_(cwd / (log_name + ".stderr")) {
    std::vector<std::string> all{STICTION_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int rc = ::posix_spawn(&pid_, STICTION_BINARY, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    REQUIRE(rc == 0);
  }
  ~Child() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  void signal(int sig) const { ::kill(pid_, sig); }
  // SIGSTOP, returning once the child has stopped: signals sent now stay pending and are
  // delivered together at resume(), which makes their order of arrival deterministic.
  void stop() {
    ::kill(pid_, SIGSTOP);
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WUNTRACED);
    REQUIRE(r == pid_);
    if (!WIFSTOPPED(status)) {  // it ended first: keep its status for wait()
      reaped_ = true;
      status_ = status;
    }
    REQUIRE(WIFSTOPPED(status));
  }
  void resume() const { ::kill(pid_, SIGCONT); }
  bool running() {
    if (reaped_) return false;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
      reaped_ = true;
      status_ = status;
      return false;
    }
    return true;
  }
  // Waits up to `limit`; the exit code, or -1 for a hang (the child is then killed) or
  // 1000 + signal for a death by signal. Sets seconds_waited.
  int wait(std::chrono::duration<double> limit = std::chrono::seconds(60)) {
    const auto start = std::chrono::steady_clock::now();
    while (running()) {
      if (std::chrono::steady_clock::now() - start > kHangGuardScale * limit) {
        ::kill(pid_, SIGKILL);
        int status = 0;
        ::waitpid(pid_, &status, 0);
        reaped_ = true;
        return -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    seconds_waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (WIFEXITED(status_)) return WEXITSTATUS(status_);
    if (WIFSIGNALED(status_)) return 1000 + WTERMSIG(status_);
    return -2;
  }
  std::string out() const { return read_text(out_); }
  std::string err() const { return read_text(err_); }

  double seconds_waited = 0.0;

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = 0;
  std::filesystem::path out_, err_;
};

// A fresh, empty directory for one test: TMP/stiction_GROUP_NAME_PID (the pid keeps two
// suites running at once apart).
inline std::filesystem::path scratch_dir(const std::string& group, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("stiction_" + group + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct RunResult {
  int code;         // as Child::wait returns it
  std::string err;  // stderr, then stdout
};

// Runs `stiction ARGS` in `cwd` to its end (bounded by Child::wait's hang guard).
inline RunResult run_child(const std::vector<std::string>& args, const std::filesystem::path& cwd) {
  Child child(args, cwd);
  const int code = child.wait();
  return {code, child.err() + child.out()};
}

// Polls `ready` every 5 ms until it holds or the child ends or `limit` passes.
template <typename Predicate>
bool wait_until(Child& child, Predicate ready, std::chrono::duration<double> limit = std::chrono::seconds(60)) {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < kHangGuardScale * limit) {
    if (ready()) return true;
    if (!child.running()) return ready();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// A run's file while it is being written: in `out` or in the run's staging directory
// `out/.stiction-staging-PID/` (services/output_dir.hpp: files land in `out` at the end).
inline bool output_exists(const std::filesystem::path& out, const std::filesystem::path& relative) {
  std::error_code ec;
  if (std::filesystem::exists(out / relative, ec)) return true;
  for (const auto& e : std::filesystem::directory_iterator(out, ec)) {
    if (e.path().filename().string().rfind(".stiction-staging-", 0) == 0 &&
        std::filesystem::exists(e.path() / relative, ec))
      return true;
  }
  return false;
}

// Every temporary a run may leave: ".NAME.tmp-*" (sys/temporaries.hpp) or older "NAME.tmp.*".
inline std::vector<std::string> temporaries_under(const std::filesystem::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find(".tmp-") != std::string::npos || name.find(".tmp.") != std::string::npos) {
      found.push_back(it->path().string());
    }
  }
  return found;
}

}  // namespace stiction::testing
