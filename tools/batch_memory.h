// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// How a batch run of the remesher (the command-line tool, the benchmark harness) has glibc's malloc keep
// the memory it frees. Process-wide, so the library itself never does this; programs that include the
// headers may do the same (the manual, "Large inputs").

#ifndef ANISO_CONFORMAL_TOOLS_BATCH_MEMORY_H
#define ANISO_CONFORMAL_TOOLS_BATCH_MEMORY_H

#include <climits>
#include <cstdlib>  // defines __GLIBC__ on glibc
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace aniso_remesh {

// glibc hands every block above its mmap threshold (at most 32 MB) back to the system when it is freed,
// and the next allocation of that size faults its pages in again, 4 KB at a time. The stages free and
// reallocate such blocks over and over (Hessians, factorisations, background triangles, integrals): at
// 1.66M input vertices 2.8M page faults and about a quarter of the run on this project's 2-core VM
// (benchmark/scaling.md). Here no block is mmap'd and the heap is trimmed only when 2 GB lie free at its
// top: freed memory is reused, the peak resident memory is the same. Elsewhere than glibc: nothing.
inline void keep_freed_memory()
{
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

} // namespace aniso_remesh

#endif // ANISO_CONFORMAL_TOOLS_BATCH_MEMORY_H
