// Transparent huge pages for the command-line programs' own heap.
//
// A cold render on llvmpipe spends a third of its CPU time in page faults:
// every texture llvmpipe allocates is zeroed page by page, and so is every
// readback and image buffer. Where the kernel gives huge pages only to memory
// that asks for them (/sys/kernel/mm/transparent_hugepage/enabled is
// "madvise", Debian's and Ubuntu's default), glibc asks for them when
// GLIBC_TUNABLES holds glibc.malloc.hugetlb=1. glibc reads that only at
// start-up, so a program that wants it starts itself again once with it set
// (docs/BENCHMARKS.md, "Session 17": 1.13-1.26x on cold renders).
#pragma once

#include <string>

namespace headlight {

// Starts this program again (same process, same arguments) with
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1 when that pays: the kernel's huge
// pages are "madvise" and the caller has not set GLIBC_TUNABLES (set, even
// empty, it is the caller's choice and is left alone). Returns when it does
// not restart, or when the restart fails.
void restartWithLargePages(char** argv);

// One line for --verbose: whether this process's heap asks for huge pages and why.
std::string largePagesNote();

}  // namespace headlight
