/* Linked into every executable of the sanitizer build (CLOTHSIM_SANITIZE=ON) only.
 *
 * LeakSanitizer looks for leaks at exit, when a library that was dlclose()d earlier is no
 * longer mapped: memory it allocated and only it pointed to is then reported as leaked, from
 * "<unknown module>", so no suppression can name it. The viewer hits this: glfwTerminate()
 * unloads libGL, libGLX_mesa and swrast_dri.so, which keep some strings for the life of the
 * process. Making dlclose() a no-op keeps every library mapped until exit, so such memory
 * stays reachable and any real leak has a symbolised stack. The executable exports this
 * definition (--export-dynamic-symbol=dlclose), so it interposes the C library's for every
 * library loaded, dlopen()ed ones too. Library destructors still run at exit. */
#include <dlfcn.h>

int dlclose(void* handle) {
  (void)handle;
  return 0;
}
