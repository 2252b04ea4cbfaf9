// libFuzzer target: any bytes through read_mlcp_bytes. Invariants: no crash, no sanitizer
// report, errors shaped "<name>: offset <k>: <reason>" with k <= size, and every accepted
// file is canonical (encoding it again gives the same bytes).
#include <string>

#include "fuzz_common.h"

namespace {

void check(const std::vector<std::uint8_t>& bytes) {
    static const std::string name = "fuzz.mlcp";
    const ode_bpp::ReadResult r = ode_bpp::read_mlcp_bytes(bytes.data(), bytes.size(), name);
    if (!r.ok) {
        const std::string prefix = name + ": offset ";
        fuzz::require(r.error.compare(0, prefix.size(), prefix) == 0);
        const std::size_t offset = std::stoull(r.error.substr(prefix.size()));
        fuzz::require(offset <= bytes.size());
        return;
    }
    std::vector<std::uint8_t> again;
    std::string error;
    fuzz::require(ode_bpp::encode_mlcp(r.file, &again, &error));
    fuzz::require(again == bytes);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    check(std::vector<std::uint8_t>(data, data + size));
    check(fuzz::resealed(data, size));
    return 0;
}
