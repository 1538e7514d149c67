/* Preloaded into simpartner-viewer by the viewer's process tests: dlclose
   does nothing. Mesa unloads its driver (swrast_dri.so) when the X display
   closes at exit, before LeakSanitizer looks; the driver's own lifetime
   allocations would then be reported from "<unknown module>" and no
   suppression could name them. With the driver still mapped, lsan.supp
   matches them by library name. Nothing else changes for a process that
   is about to exit anyway. */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
