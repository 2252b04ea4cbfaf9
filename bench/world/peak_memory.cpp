// bench/world/peak_memory.cpp
#include "peak_memory.h"

#include <sys/resource.h>

namespace ode_bpp::bench {

long peak_resident_kb() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return -1;
    return usage.ru_maxrss;
}

}  // namespace ode_bpp::bench
