// One Catch2 main for every test program. The tests run the program many times: its step
// check cache (app/step_check_cache.hpp) stays off unless a test sets STICTION_CACHE_DIR
// itself, so a test run writes nothing into the user's (or CI's) home directory.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cstdlib>

int main(int argc, char* argv[]) {
  ::setenv("STICTION_CACHE_DIR", "off", 0);
  return Catch::Session().run(argc, argv);
}
