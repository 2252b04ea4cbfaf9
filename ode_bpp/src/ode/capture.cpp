// Capture: the island's Problem view (ode/island_view.h, the hook's own) copied into a file image.
#include "ode_bpp/capture.h"

#include <ode/ode.h>

#include <algorithm>
#include <cstdio>
#include <new>

#include "ode/assemble.h"
#include "ode/island_view.h"

namespace ode_bpp {

namespace {

std::nullopt_t no_file(std::string* error, const std::string& reason) {
    if (error) *error = reason;
    return std::nullopt;
}

/// %.17g: every double read back exactly.
std::string format_double(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

void capture_metadata(const dMLCP& p, const Metadata& meta, MlcpFile* f) {
    f->meta = meta;
    if (!f->meta.find("step_size")) f->meta.set("step_size", format_double(p.stepsize));
    if (p.world && !f->meta.find("cfm")) f->meta.set("cfm", format_double(dWorldGetCFM(p.world)));
    if (p.world && !f->meta.find("erp")) f->meta.set("erp", format_double(dWorldGetERP(p.world)));
}

std::optional<std::string> check_island(const dMLCP& p) {
    const bool has_matrix = p.A != nullptr || ode::has_sparse_form(p);
    if (p.m < 0 || (p.m > 0 && (!has_matrix || !p.pairsbx || !p.pairslh)) || p.skip < p.m)
        return "ODE island: bad sizes or null arrays";
    if (p.nj > 0 && p.joints != nullptr) {
        const int k = ode::first_untiled_joint(p);
        if (k >= 0)
            return "ODE island: joint " + std::to_string(k) + " has rows " + std::to_string(p.joints[k].row) + " .. +" +
                   std::to_string(p.joints[k].m) + ", expected to start at " +
                   std::to_string(k == 0 ? 0 : p.joints[k - 1].row + p.joints[k - 1].m);
    }
    return std::nullopt;
}

}  // namespace

std::optional<MlcpFile> capture_from_ode(const dMLCP& p, const Metadata& meta, std::string* error) {
    if (auto e = check_island(p)) return no_file(error, *e);
    try {
        ode::IslandView view;
        std::string reason;
        std::optional<MlcpFile> f = copy_problem(view.of(p), {}, nullptr, &reason);
        if (!f) return no_file(error, "ODE island: " + reason);
        if (p.nj > 0 && p.joints != nullptr) f->num_bodies = std::max(f->num_bodies, p.nb);
        capture_metadata(p, meta, &*f);
        return f;
    } catch (const std::bad_alloc&) {
        return no_file(error, "out of memory");
    }
}

bool write_mlcp_from_ode(const std::string& path, const dMLCP& problem, const Metadata& meta, std::string* error) {
    std::string reason;
    const auto file = capture_from_ode(problem, meta, &reason);
    if (!file) {
        if (error) *error = path + ": " + reason;
        return false;
    }
    return write_mlcp(path, *file, error);
}

}  // namespace ode_bpp
