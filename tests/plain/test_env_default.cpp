// ODE_LCP_SOLVER switches an unchanged program's worlds. ctest runs this file once per case
// (tests/CMakeLists.txt) with ODE_LCP_SOLVER set and EXPECT_SOLVER naming the expected result;
// run by hand without EXPECT_SOLVER it skips.
#include <gtest/gtest.h>

#include <cstdarg>
#include <cstdlib>
#include <string>

#include <ode/ode.h>

namespace {

std::string g_messages;
void capture(int, const char* msg, va_list ap) {
    char buf[1024];
    vsnprintf(buf, sizeof buf, msg, ap);
    g_messages += buf;
    g_messages += '\n';
}

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

TEST(EnvDefault, WorldsFollowODE_LCP_SOLVER) {
    const char* expect = std::getenv("EXPECT_SOLVER");
    if (expect == nullptr) GTEST_SKIP() << "run through ctest with EXPECT_SOLVER and ODE_LCP_SOLVER";
    dInitODE2(0);
    dSetMessageHandler(&capture);
    dWorldID w1 = dWorldCreate(), w2 = dWorldCreate();
    EXPECT_STREQ(dWorldGetMLCPSolver(w1), expect);
    EXPECT_STREQ(dWorldGetMLCPSolver(w2), expect);
    EXPECT_STREQ(dGetDefaultMLCPSolver(), expect);
    const char* bad = std::getenv("EXPECT_WARNING");
    if (bad != nullptr) {
        // one clear warning naming the bad value and listing the valid names, however often asked
        EXPECT_EQ(count(g_messages, "is not a known MLCP solver"), 1) << g_messages;
        EXPECT_NE(g_messages.find(bad), std::string::npos) << g_messages;
        EXPECT_NE(g_messages.find("dantzig"), std::string::npos) << g_messages;
    } else {
        EXPECT_EQ(g_messages, "");
    }
    dWorldDestroy(w1);
    dWorldDestroy(w2);
    dCloseODE();
}

}  // namespace
