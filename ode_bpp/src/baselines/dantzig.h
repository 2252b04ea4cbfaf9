// ODE's stock Dantzig as a baseline (Method::Dantzig) and as the last step of solve()'s fallback
// chain. The core holds only the slot: the ODE glue (ode/dantzig_backend.cpp, in libode_bpp)
// installs ODE's dSolveMLCPDantzig into it when the library loads, so ode_bpp_core builds, links
// and runs without ODE, and a program that uses the core alone may install a Dantzig of its own.
#pragma once

#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::baselines {

/// A Dantzig solver. problem: validated, original space; A: its matrix as compressed rows
/// (original order). x: out, n entries, possibly non-finite (ODE does not check). False when the
/// solver refused the call (e.g. no memory); x is then zero.
using DantzigBackend = bool (*)(const Problem& problem, const linalg::SymmetricRows& A, std::vector<double>& x);

/// Installs the solver behind solve_dantzig (null: none). Call it before solves start: the slot is
/// read without synchronization.
void install_dantzig(DantzigBackend backend);

enum class DantzigOutcome {
    Solved,       ///< x holds the backend's answer
    Refused,      ///< the backend refused the call; x is zero
    Unavailable,  ///< no backend installed (ode_bpp_core without the ODE glue); x is zero
};

/// Runs the installed backend (see DantzigBackend).
DantzigOutcome solve_dantzig(const Problem& problem, const linalg::SymmetricRows& A, std::vector<double>& x);

}  // namespace ode_bpp::baselines
