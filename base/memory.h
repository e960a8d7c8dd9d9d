// Running out of memory as an error like any other: the peak the process reached, the message
// the tools print when an allocation fails (std::bad_alloc, caught at the pipeline's and the
// drivers' level), and `--max-memory` (an address-space limit, RLIMIT_AS).
#pragma once

#include <cstdint>
#include <string>

#include "base/result.h"

namespace tranche {

// The most resident memory the process has used so far, in bytes (getrusage).
uint64_t peak_memory_bytes();

// "out of memory while <doing> (peak 812 MB[, --max-memory 1000 MB]); <advice>", naming `where`.
Error out_of_memory(const std::string& where, const std::string& doing,
                    const std::string& advice = "try a larger layer height or a smaller model");

// Limits the process's address space to `mb` megabytes (setrlimit RLIMIT_AS, the soft limit;
// never above the hard limit). Allocations beyond fail, and the run stops with out_of_memory().
Status set_memory_limit(uint64_t mb);
// The limit set_memory_limit() set, in MB (0: none).
uint64_t memory_limit_mb();

// Loads the unwinder (libgcc_s) into glibc's reach now; the tools call it first thing in main().
// glibc dlopen()s it the first time it needs it itself: for an exception that passes through one
// of its own frames (std::call_once runs its function inside pthread_once), backtrace(),
// pthread_cancel. That dlopen takes a little memory; when an allocation has just failed there is
// none, and glibc then aborts ("libgcc_s.so.1 must be installed for unwinding to work") instead
// of letting the std::bad_alloc reach the handler that prints out_of_memory(). Loaded at start,
// while there is memory, it is never needed again. Returns false when the unwinder could not be
// loaded (then nothing more can be done).
bool load_unwinder();

}  // namespace tranche
