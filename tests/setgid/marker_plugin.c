/* A plug-in that only leaves a mark when a process loads it (MARK_PATH is set at compile time). */
#include <stdio.h>

__attribute__((constructor)) static void leave_mark(void)
{
    FILE *f = fopen(MARK_PATH, "w");
    if (f != NULL) fclose(f);
}
