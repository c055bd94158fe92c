// memory_use.hpp - the process's resident memory, from /proc/self/status
// (Linux): now (VmRSS) and its peak (VmHWM), and a reset of that peak (so
// that one phase's peak can be measured after another's).
#pragma once
#include <cstddef>

namespace clrt {

// Bytes; 0 where /proc cannot be read.
size_t resident_bytes();
size_t peak_resident_bytes();
// Sets the peak to the present resident size (writing 5 to
// /proc/self/clear_refs, Linux >= 4.0). False when that is refused: the
// peak is then the process's since it started.
bool reset_peak_resident();

}  // namespace clrt
