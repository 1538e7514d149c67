// AddressSanitizer's defaults for every program of a sanitized build
// (SP_SANITIZE, CMakeLists.txt); ASAN_OPTIONS still overrides each flag.
//
// intercept_tls_get_addr=0: the runtimes of GCC 12 and LLVM before 17 take a
// dynamic TLS block whose address is 16 past a page boundary for one with
// glibc 2.19's header, and record the two words before it (ASan's own chunk
// header) as the block's start and size. Since glibc 2.25 there is no such
// header; a small malloc'd block lands there by chance, and at exit
// LeakSanitizer's tracer scans the bogus range and dies ("Tracer caught
// signal 11"). Which block lands where depends on thread timing, so it
// failed programs that load SDL's or Mesa's libraries about once a suite
// under load. tests/support/dynamic_tls_probe.cpp fails every time without
// this. Leak checking stays on: glibc keeps those blocks on the heap,
// reachable from each thread's static TLS, which is still scanned.
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
