// ode_bpp/capture.h: islands of the patched world step written as MLCP files (io.h,
// docs/mlcp-format.md). Part of the ODE glue (libode_bpp); the file format itself (io.h) needs no
// ODE.
#pragma once

#include "ode_bpp/export.h"

#include <optional>
#include <string>

#include <ode/mlcp.h>

#include "ode_bpp/io.h"

namespace ode_bpp {

/// Copies the island ODE handed to the MLCP observer or solver: A's lower triangle (ODE's dense
/// A, or assembled from J, J M^-1 and the CFM in the sparse form), pairsbx/pairslh
/// de-interleaved, and joint k as block k (rows joints[k].row .. +m, bodies joints[k].body[0..1])
/// over nb bodies. Must be called before the solve (Dantzig destroys A). Sets metadata step_size
/// and, if the world is known, cfm and erp, unless meta already has them. Fails, with a message,
/// when the joints do not tile the rows or the structure is otherwise invalid.
ODE_BPP_API std::optional<MlcpFile> capture_from_ode(const dMLCP& problem, const Metadata& meta, std::string* error);

/// capture_from_ode followed by write_mlcp: true when the file was written.
/// error (here and above): out, may be null; the reason, set only on failure.
ODE_BPP_API bool write_mlcp_from_ode(const std::string& path, const dMLCP& problem, const Metadata& meta,
                         std::string* error);

}  // namespace ode_bpp
