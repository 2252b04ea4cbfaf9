// ode_bpp/workspace.h: the memory a solve works in, kept by the caller from solve to solve.
#pragma once

#include <memory>

#include "ode_bpp/export.h"

namespace ode_bpp {

struct Result;

/// The scratch memory of solve(): every buffer the solver needs besides the problem, the answer
/// and the Result. Buffers grow to the largest problem met and keep their capacity, so that a
/// solve on a warm workspace allocates nothing beyond its Result, and nothing at all on a small
/// island (pivoting/small_island.h) once a spent Result has been handed back (recycle).
///
/// One solve per workspace at a time: a workspace must not be shared by solves that run
/// concurrently (threads), and a solve never starts another on its own workspace. Independent
/// workspaces may be used from any threads. Movable, not copyable; creating one allocates only
/// its handle.
class ODE_BPP_API Workspace {
public:
    Workspace();
    ~Workspace();
    Workspace(Workspace&&) noexcept;
    Workspace& operator=(Workspace&&) noexcept;
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;

    /// The buffers of each part of the solver (defined inside the library, workspace_parts.h).
    struct Parts;
    /// For the library's own use (the type is incomplete outside it): the parts, created by the
    /// first call, then the same object until the workspace is destroyed or moved from.
    Parts& parts();

    /// Keeps the storage of a Result the caller is done with (its index set's capacity) for the
    /// next solve's Result; `spent` is left valid but unspecified. Optional: it saves a caller that
    /// solves island after island (the ODE hook) an allocation and a release per solve.
    void recycle(Result&& spent);

private:
    std::unique_ptr<Parts> parts_;
};

}  // namespace ode_bpp
