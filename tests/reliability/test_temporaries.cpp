// sys/temporaries: exclusive, unpredictable names in the target's directory, tracked until
// renamed, and removable from a signal handler.
#include <filesystem>
#include <set>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "sys/temporaries.hpp"

namespace fs = std::filesystem;

TEST_CASE("temporaries are exclusive, hidden and in the target's directory", "[temporaries]") {
  const fs::path dir = fs::temp_directory_path() / ("stiction_temporaries_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::set<std::string> names;
  for (int i = 0; i < 50; ++i) {
    const stiction::sys::Temporary t = stiction::sys::create_temporary(dir / "out.csv");
    CHECK(t.fd >= 0);
    ::close(t.fd);
    CHECK(t.path.parent_path() == dir);
    CHECK(t.path.filename().string().rfind(".out.csv.tmp-", 0) == 0);
    CHECK(t.path.filename().string().size() == std::string(".out.csv.tmp-").size() + 16);
    names.insert(t.path.string());
  }
  CHECK(names.size() == 50);  // never the same name twice
  // A tracked temporary goes with remove_registered_temporaries (the second-signal path);
  // a forgotten one (already renamed by its owner) is left alone.
  const stiction::sys::Temporary kept = stiction::sys::create_temporary(dir / "kept.png");
  ::close(kept.fd);
  stiction::sys::forget_temporary(kept.path);
  stiction::sys::remove_registered_temporaries();
  for (const std::string& n : names) CHECK_FALSE(fs::exists(n));
  CHECK(fs::exists(kept.path));
  // A directory that does not exist is an error, not a file elsewhere.
  CHECK_THROWS_AS(stiction::sys::create_temporary(dir / "missing" / "x"), std::system_error);
  fs::remove_all(dir);
}
