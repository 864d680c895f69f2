#pragma once
// The one skip convention of the tests: print "SKIPPED: reason" and exit with status 77, which
// CTest shows as skipped (SKIP_RETURN_CODE 77, cmake/SonarloopTests.cmake) with the reason in
// the test's output.
//
// A skip ends the whole executable, so a test case that may skip while its neighbours must still
// run carries the Catch2 tag [may_skip]: sonarloop_add_test then registers the file's cases
// twice, `test_NAME` (every case but those) and `test_NAME_may_skip` (only those), and a skip
// shows as exactly that entry skipped. Several [may_skip] cases of one file share the entry:
// give them the same reason to skip (e.g. the same missing kernel feature).
#include <cstdio>
#include <cstdlib>
#include <string>

namespace sonarloop::testing {

[[noreturn]] inline void skip_test(const std::string& reason) {
  std::printf("SKIPPED: %s\n", reason.c_str());
  std::fflush(stdout);
  std::exit(77);
}

}  // namespace sonarloop::testing
