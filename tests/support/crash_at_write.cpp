// Preloaded into `gearsph run` by the crash-point tests (LD_PRELOAD): kills
// the process with SIGKILL just before its Nth pwrite, the call HDF5's
// default file driver writes with. A sweep over N stops a run between every
// two writes of results.h5, which random kill times reach only by luck.
//
//   GEARSPH_CRASH_AT_WRITE=N      SIGKILL before pwrite number N (from 1)
//   GEARSPH_WRITE_COUNT_FILE=F    at exit, write the number of pwrites to F
#include <dlfcn.h>
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace {

using Pwrite = ssize_t (*)(int, const void*, size_t, off_t);

std::atomic<long> writes{0};

long crash_at() {
  static const long at = [] {
    const char* s = std::getenv("GEARSPH_CRASH_AT_WRITE");
    return s ? std::atol(s) : -1L;
  }();
  return at;
}

ssize_t counted_pwrite(int fd, const void* buf, size_t n, off_t offset) {
  static const auto real = reinterpret_cast<Pwrite>(dlsym(RTLD_NEXT, "pwrite"));
  const long k = ++writes;
  if (crash_at() > 0 && k >= crash_at()) ::kill(::getpid(), SIGKILL);
  return real(fd, buf, n, offset);
}

struct CountReport {
  ~CountReport() {
    const char* path = std::getenv("GEARSPH_WRITE_COUNT_FILE");
    if (!path) return;
    if (FILE* f = std::fopen(path, "w")) {
      std::fprintf(f, "%ld\n", writes.load());
      std::fclose(f);
    }
  }
} report;

}  // namespace

extern "C" {
ssize_t pwrite(int fd, const void* buf, size_t n, off_t offset) {
  return counted_pwrite(fd, buf, n, offset);
}
ssize_t pwrite64(int fd, const void* buf, size_t n, off_t offset) {
  return counted_pwrite(fd, buf, n, offset);
}
}
