// Counts heap allocations on the threads that asked for it (tests/support/allocation_counter.h),
// for the test executables that link it. malloc itself is counted, so that operator new (which
// allocates through malloc), Eigen's aligned malloc and C allocations are all seen:
// - normally by interposing glibc's malloc family for the executable (each replacement forwards
//   to glibc's own __libc_* entry point);
// - under AddressSanitizer or ThreadSanitizer, which own malloc, through their allocation hooks
//   (called on the allocating thread for every allocation, operator new included).
#include "tests/support/allocation_counter.h"

#include <cstddef>

// Whether a sanitizer owns malloc: GCC says so with __SANITIZE_*__, clang 14 only through
// __has_feature.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SONARLOOP_SANITIZER_OWNS_MALLOC 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SONARLOOP_SANITIZER_OWNS_MALLOC 1
#endif
#endif

namespace {
// initial-exec TLS of the executable itself: reading it never allocates
thread_local bool g_counting = false;
thread_local long g_allocations = 0;

void count_one() {
  if (g_counting) ++g_allocations;
}
}  // namespace

namespace sonarloop::testing {

void set_allocation_counting(bool on) {
  if (on) g_allocations = 0;
  g_counting = on;
}

long counted_allocations() {
  return g_allocations;
}

}  // namespace sonarloop::testing

#ifdef SONARLOOP_SANITIZER_OWNS_MALLOC
// from the sanitizer runtime (libasan); GCC does not ship <sanitizer/allocator_interface.h>
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void on_malloc(const volatile void*, std::size_t) {
  count_one();
}
void on_free(const volatile void*) {}
const int g_hooks_installed = __sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);
}  // namespace
#else
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t n, std::size_t size) noexcept;
void* __libc_realloc(void* p, std::size_t size) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void __libc_free(void* p) noexcept;

void* malloc(std::size_t size) noexcept {
  count_one();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  count_one();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) noexcept {
  count_one();
  return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  count_one();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  count_one();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  count_one();
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void free(void* p) noexcept {
  __libc_free(p);
}
}
#endif
