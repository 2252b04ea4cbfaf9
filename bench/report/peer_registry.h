// Peer solvers (other libraries' MLCP solvers) as bench_corpus sees them.
//
// bench_corpus links this registry always; the adapters in bench/peers add themselves to it,
// through a static PeerRegistration in a source compiled into bench_corpus, only when their
// Debian package was found at configure time. Without peers the registry is empty and
// bench_corpus times ode_bpp's methods alone.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp::bench {

/// What a peer said about its own answer (its answer is judged by our residuals either way).
enum class PeerStatus {
    Solved,   ///< the peer reported success
    Failed,   ///< the peer reported failure; x is whatever it left (zeros if it left nothing usable)
    Skipped,  ///< not attempted (the problem is outside the peer's practical size); x is zero
    Iterated, ///< an iterative peer ran its fixed sweep count (no claim; the residual judges x)
};

/// Name written into bench_corpus's status column ("solved", "failed", "skipped", "iterated").
const char* to_string(PeerStatus status);

/// One peer configuration, e.g. "bullet-pgs-35".
struct PeerMethod {
    std::string name;
    int iterations = 0;  ///< sweep count for iterative peers, 0 for direct ones
    /// Solves problem (original row order, ODE's MLCP of solver.h) and writes x (n entries).
    std::function<PeerStatus(const Problem& problem, double* x)> solve;
};

/// Builds a package's peer methods; iterations: the sweep counts wanted for iterative peers.
using PeerFactory = std::function<std::vector<PeerMethod>(const std::vector<int>& iterations)>;

/// Every factory registered in this executable (empty when it was built without peers).
std::vector<PeerFactory>& peer_factories();

/// Adds a factory at static-initialization time: `const PeerRegistration reg{make_my_peers};`.
struct PeerRegistration {
    explicit PeerRegistration(PeerFactory factory);
};

/// All peer methods of every registered factory, for the given sweep counts.
std::vector<PeerMethod> all_peer_methods(const std::vector<int>& iterations);

}  // namespace ode_bpp::bench
