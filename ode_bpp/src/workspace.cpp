#include "workspace_parts.h"

namespace ode_bpp {

Workspace::Workspace() = default;
Workspace::~Workspace() = default;
Workspace::Workspace(Workspace&&) noexcept = default;
Workspace& Workspace::operator=(Workspace&&) noexcept = default;

Workspace::Parts& Workspace::parts() {
    if (!parts_) parts_ = std::make_unique<Parts>();  // on first use, also after a move
    return *parts_;
}

void Workspace::recycle(Result&& spent) { parts().spare_states.swap(spent.states); }

Workspace& thread_workspace() {
    thread_local Workspace workspace;
    return workspace;
}

}  // namespace ode_bpp
