// Freed memory kept in the process (see freed_memory.h).
#include "freed_memory.h"

#include <malloc.h>

#include <mutex>

namespace trackbed::render {

void KeepFreedMemory() {
#ifdef __GLIBC__
  static std::once_flag once;
  std::call_once(once, [] {
    mallopt(M_TRIM_THRESHOLD, 256 << 20);  // keep up to 256 MiB freed at the heap's top
    mallopt(M_MMAP_THRESHOLD, 32 << 20);   // map only blocks of 32 MiB and more
  });
#endif
}

}  // namespace trackbed::render
