/* A stand-in for another libode, for the launcher's refusal tests: built as a shared library with
 * a chosen soname, it carries the precision marker of ODE 0.16's configuration string
 * (dGetConfiguration), which is what the launcher reads in a real libode. */
#ifndef FAKE_PRECISION
#error "define FAKE_PRECISION as ODE_single_precision or ODE_double_precision"
#endif
#define STR2(x) #x
#define STR(x) STR2(x)

const char *dGetConfiguration(void) { return "ODE " STR(FAKE_PRECISION); }
int dCheckConfiguration(const char *token) { (void)token; return 0; }
int dInitODE2(unsigned flags) { (void)flags; return 1; }
