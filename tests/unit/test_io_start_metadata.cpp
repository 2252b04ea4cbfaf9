// A warm start in a file's metadata (ode_bpp/io.h: set_start_metadata, start_from_metadata):
// round trips through the keys and the file, and values that do not fit the problem are refused
// with a message naming the key.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ode_bpp/io.h"

namespace {

using ode_bpp::Metadata;
using ode_bpp::RowState;
using ode_bpp::Start;

Metadata with(const std::string& key, const std::string& value) {
    Metadata meta;
    meta.set(key, value);
    return meta;
}

std::string refusal(const Metadata& meta, int n) {
    std::string error;
    EXPECT_FALSE(ode_bpp::start_from_metadata(meta, n, &error).has_value());
    return error;
}

TEST(IoStartMetadata, IndexSetAndOrderingRoundTrip) {
    Start start;
    start.states = {RowState::Free, RowState::AtLo, RowState::AtHi, RowState::Free};
    start.ordering = {3, 0, 2, 1};
    Metadata meta;
    meta.set("scene", "winch");
    ode_bpp::set_start_metadata(start, meta);
    ASSERT_NE(meta.find(ode_bpp::kWarmStartKey), nullptr);
    EXPECT_EQ(*meta.find(ode_bpp::kWarmStartKey), "FLHF");
    EXPECT_EQ(*meta.find(ode_bpp::kOrderingKey), "3,0,2,1");
    std::string error;
    const auto back = ode_bpp::start_from_metadata(meta, 4, &error);
    ASSERT_TRUE(back.has_value()) << error;
    EXPECT_EQ(back->states, start.states);
    EXPECT_EQ(back->ordering, start.ordering);
}

TEST(IoStartMetadata, SurvivesTheFile) {
    ode_bpp::MlcpFile file;
    file.n = 2;
    file.A = {2, 1, 1, 2};
    file.b = {1, -1};
    file.lo = {0, 0};
    file.hi = {1, 1};
    Start start;
    start.states = {RowState::AtHi, RowState::AtLo};
    start.ordering = {1, 0};
    ode_bpp::set_start_metadata(start, file.meta);
    std::vector<std::uint8_t> bytes;
    std::string error;
    ASSERT_TRUE(ode_bpp::encode_mlcp(file, &bytes, &error)) << error;
    const ode_bpp::ReadResult read = ode_bpp::read_mlcp_bytes(bytes.data(), bytes.size(), "memory");
    ASSERT_TRUE(read.ok) << read.error;
    const auto back = ode_bpp::start_from_metadata(read.file.meta, read.file.n, &error);
    ASSERT_TRUE(back.has_value()) << error;
    EXPECT_EQ(back->states, start.states);
    EXPECT_EQ(back->ordering, start.ordering);
}

TEST(IoStartMetadata, AbsentKeysGiveAColdStart) {
    std::string error;
    const auto start = ode_bpp::start_from_metadata(with("scene", "crane"), 5, &error);
    ASSERT_TRUE(start.has_value()) << error;
    EXPECT_TRUE(start->states.empty());
    EXPECT_TRUE(start->ordering.empty());
    Metadata meta;
    ode_bpp::set_start_metadata(Start{}, meta);
    EXPECT_TRUE(meta.entries.empty()) << "an empty start writes no key";
}

TEST(IoStartMetadata, RefusesAnIndexSetThatDoesNotFit) {
    EXPECT_EQ(refusal(with("warm_start", "FFL"), 4), "warm_start has 3 rows, n = 4");
    EXPECT_EQ(refusal(with("warm_start", "FXLF"), 4), "warm_start: row 1 is 'X', not F, L or H");
    EXPECT_EQ(refusal(with("warm_start", ""), 1), "warm_start has 0 rows, n = 1");
}

TEST(IoStartMetadata, RefusesAnOrderingThatIsNoPermutation) {
    const std::string not_new = "ordering: entry 2 is not a new row in [0, 3)";
    EXPECT_EQ(refusal(with("ordering", "0,1,1"), 3), not_new);
    EXPECT_EQ(refusal(with("ordering", "0,1,3"), 3), not_new);
    EXPECT_EQ(refusal(with("ordering", "0,1,-2"), 3), not_new);
    EXPECT_EQ(refusal(with("ordering", "0,1,"), 3), not_new);
    EXPECT_EQ(refusal(with("ordering", "0,1,2x"), 3), not_new);
    EXPECT_EQ(refusal(with("ordering", "0,1"), 3), "ordering has 2 entries, n = 3");
    EXPECT_EQ(refusal(with("ordering", "0,1,2,0"), 3), "ordering: entry 3 is not a new row in [0, 3)");
    EXPECT_EQ(refusal(with("ordering", "99999999999999999999"), 3), "ordering: entry 0 is not a new row in [0, 3)");
    EXPECT_EQ(refusal(with("ordering", ""), 3), "ordering: entry 0 is not a new row in [0, 3)");
}

}  // namespace
