// ode-bpp-run-solvers: prints, on one line, the MLCP solver names that ODE knows once libode_bpp
// is loaded (dListMLCPSolvers: "dantzig, bpp-chol, ..."). ode-bpp-run checks --solver and
// --quickstep against it; run on the libraries the launcher puts first, it also shows that they
// are the patched libode and a loadable libode_bpp. Exit status 0, or 1 if no name is registered.
#include <ode/mlcp.h>

#include <cstdio>

#include "ode_bpp/ode.h"

int main() {
    ode_bpp_register_solvers();  // a use of libode_bpp, so that --as-needed keeps it
    const char* names = dListMLCPSolvers();
    if (names == nullptr || names[0] == '\0') return 1;
    std::puts(names);
    return 0;
}
