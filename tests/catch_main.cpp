// One Catch2 main for every test program. The tests run the program many times: its step
// check cache (app/step_check_cache.hpp) stays off unless a test sets STICTION_CACHE_DIR
// itself, so a test run writes nothing into the user's (or CI's) home directory.
//
// A test whose name holds ';' never runs under CTest: catch_discover_tests passes the name
// as a CMake list, cut at the ';', and Catch then matches no test and exits 0. Six tests sat
// like that unseen; every test program now refuses to start with such a name. And a run whose
// test spec matches nothing fails (Catch's "NoTests" warning as an error) instead of passing.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>

int main(int argc, char* argv[]) {
  ::setenv("STICTION_CACHE_DIR", "off", 0);
  bool named_badly = false;
  for (const Catch::TestCase& test : Catch::getRegistryHub().getTestCaseRegistry().getAllTests()) {
    if (test.getTestCaseInfo().name.find(';') != std::string::npos) {
      std::fprintf(stderr, "test name with ';' (CTest would never run it): %s\n",
                   test.getTestCaseInfo().name.c_str());
      named_badly = true;
    }
  }
  if (named_badly) return 2;
  Catch::Session session;
  if (const int rc = session.applyCommandLine(argc, argv); rc != 0) return rc;
  session.configData().warnings =
      static_cast<Catch::WarnAbout::What>(session.configData().warnings | Catch::WarnAbout::NoTests);
  return session.run();
}
