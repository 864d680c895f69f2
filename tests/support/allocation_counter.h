#pragma once
// Counts heap allocations made by a piece of code on the calling thread, for the tests that
// check "no allocation per ping / per frame". Linking the object library
// sonarloop_test_allocation_counter (tests/CMakeLists.txt) counts every malloc of the test
// executable (operator new and Eigen included), also under AddressSanitizer
// (allocation_counter.cpp); other threads are not counted.
#include <utility>

namespace sonarloop::testing {

// Starts (true) or stops (false) counting on this thread; starting resets the count.
void set_allocation_counting(bool on);
// Allocations counted on this thread since counting last started.
long counted_allocations();

// Allocations made by f() on this thread.
template <class F>
long allocations_in(F&& f) {
  set_allocation_counting(true);
  std::forward<F>(f)();
  set_allocation_counting(false);
  return counted_allocations();
}

}  // namespace sonarloop::testing
