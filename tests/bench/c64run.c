/* CLIPS 6.4 as the bench's clipspy driver runs it (load, reset, run), without Python:
 * calls clipspy's own library. Built by tests/bench/shapes.py with -DCLIPS_SO="path".
 * Usage: c64run PROGRAM.clp [norun]
 *        c64run -f2 BATCH.clp   (CLIPS 6.4's own main: RerouteStdin, CommandLoop;
 *                                tests/bench/others.py runs batch files this way) */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

typedef void *(*create_fn)(void);
typedef int (*load_fn)(void *, const char *);
typedef void (*reset_fn)(void *);
typedef long long (*run_fn)(void *, long long);
typedef void (*reroute_fn)(void *, int, char **);
typedef void (*loop_fn)(void *);

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: c64run PROGRAM.clp [norun]\n");
    return 2;
  }
  void *lib = dlopen(CLIPS_SO, RTLD_NOW);
  if (!lib) {
    fprintf(stderr, "%s\n", dlerror());
    return 2;
  }
  create_fn create = (create_fn)dlsym(lib, "CreateEnvironment");
  if (argv[1][0] == '-') {
    reroute_fn reroute = (reroute_fn)dlsym(lib, "RerouteStdin");
    loop_fn loop = (loop_fn)dlsym(lib, "CommandLoop");
    if (!create || !reroute || !loop) {
      fprintf(stderr, "missing CLIPS entry points in %s\n", CLIPS_SO);
      return 2;
    }
    void *env = create();
    reroute(env, argc, argv);
    loop(env); /* returns only by `(exit)`, which exits the process */
    return 0;
  }
  load_fn load = (load_fn)dlsym(lib, "Load");
  reset_fn reset = (reset_fn)dlsym(lib, "Reset");
  run_fn run = (run_fn)dlsym(lib, "Run");
  if (!create || !load || !reset || !run) {
    fprintf(stderr, "missing CLIPS entry points in %s\n", CLIPS_SO);
    return 2;
  }
  void *env = create();
  if (load(env, argv[1]) != 0) { /* LE_NO_ERROR */
    fprintf(stderr, "load failed: %s\n", argv[1]);
    return 3;
  }
  reset(env);
  if (argc > 2 && strcmp(argv[2], "norun") == 0)
    return 0;
  long long fired = run(env, -1);
  fflush(stdout);
  fprintf(stderr, "fired %lld\n", fired);
  return 0;
}
