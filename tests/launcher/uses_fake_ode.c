/* Calls the stand-in libode (fake_ode.c) so that it is NEEDED, and says that it ran. */
#include <stdio.h>

int dInitODE2(unsigned flags);

int main(void) {
    dInitODE2(0);
    puts("uses_fake_ode ran");
    return 0;
}
