// ODE initialised for one test's scope (dInitODE2 / dCloseODE), shared by the integration suites.
#pragma once

#include <ode/ode.h>

namespace ode_bpp::test {

struct OdeLifetime {
    OdeLifetime() { dInitODE2(0); }
    ~OdeLifetime() { dCloseODE(); }
    OdeLifetime(const OdeLifetime&) = delete;
    OdeLifetime& operator=(const OdeLifetime&) = delete;
};

}  // namespace ode_bpp::test
