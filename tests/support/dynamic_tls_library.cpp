// A library with a thread-local variable of the global-dynamic model, as
// dlopen'd graphics libraries have: each thread's first use allocates its
// block through __tls_get_addr (dynamic_tls_probe.cpp).
namespace {
thread_local int uses = 0;
}  // namespace

extern "C" int UseThreadLocal() { return ++uses; }
