// Freed memory kept in the process for llvmpipe's per-frame allocations. Private to the
// renderer.
//
// llvmpipe allocates and frees its per-frame working memory (vertex and bin
// storage, buffer uploads) at every frame. glibc hands freed memory at the
// top of the heap back to the kernel beyond 128 KiB, and blocks of 128 KiB and
// more are mapped and unmapped each time, so every frame faulted the same
// pages in again: 3 % of the closed loop's CPU outdoors was the kernel's
// page-fault handler. Keeping freed memory in the process (a process-wide
// setting, harmless to the rest) makes the loop 1.1x faster with the same
// bytes (docs/rendering.md).
// Called by every renderer's constructor, acting once per process: mallopt is not
// thread-safe, and the setting is the process's anyway.
#pragma once

namespace trackbed::render {

/// Keeps up to 256 MiB freed at the heap's top and maps only blocks of 32 MiB and more
/// (glibc's mallopt; nothing elsewhere). Once per process, thread-safe.
void KeepFreedMemory();

}  // namespace trackbed::render
