// Loads a library with dynamic TLS (dynamic_tls_library.cpp), uses it on
// a thread that is still alive at exit, and exits through LeakSanitizer's
// check. Without intercept_tls_get_addr=0 (common/src/sanitizer_options.cpp)
// GCC 12's runtime records a bogus TLS range for that thread and the leak
// check's tracer dies on it: exit status 1 and "LeakSanitizer has
// encountered a fatal error", every run on Debian 12.
//   sp_dynamic_tls_probe LIBRARY [THREADS]
#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <thread>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: sp_dynamic_tls_probe LIBRARY [THREADS]\n");
    return 2;
  }
  void* library = dlopen(argv[1], RTLD_NOW);
  if (library == nullptr) {
    std::fprintf(stderr, "sp_dynamic_tls_probe: %s\n", dlerror());
    return 2;
  }
  auto use = reinterpret_cast<int (*)()>(dlsym(library, "UseThreadLocal"));
  if (use == nullptr) {
    std::fprintf(stderr, "sp_dynamic_tls_probe: %s has no UseThreadLocal\n", argv[1]);
    return 2;
  }
  const int threads = argc > 2 ? std::atoi(argv[2]) : 4;
  std::atomic<int> ready{0};
  for (int i = 0; i < threads; ++i)
    std::thread([&] {
      use();
      ++ready;
      pause();  // alive at exit, when the leak check scans its TLS
    }).detach();
  while (ready < threads) usleep(1000);
  use();
  std::printf("sp_dynamic_tls_probe: %d threads used the library's thread-local\n", threads);
  std::exit(0);  // through the leak check
}
