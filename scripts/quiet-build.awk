# Filters `cmake --build` output (Makefile generator) for `make build`: the compiler's messages
# and anything unexpected pass through; per-file lines become a progress line per 10 % step.
#   awk -f scripts/quiet-build.awk      (stdin: the build's stdout and stderr)
# The full output stays in the build log the Makefile keeps beside it.
function progress(line) { return substr(line, 2, index(line, "%") - 2) + 0 }
/^\[ *[0-9]+%\] (Building|Linking|Generating) / {
    worked = 1
    p = progress($0)
    if (p >= shown) { printf "[build] %3d %%\n", p; shown = (int(p / 10) + 1) * 10 }
    next
}
/^\[ *[0-9]+%\] Built target / { next }
/^(Consolidate compiler generated dependencies|Scanning dependencies) of target / { next }
/^g?make(\[[0-9]+\])?: (Entering|Leaving) directory / { next }
{ print; fflush() }
END { print worked ? "[build] done" : "[build] up to date" }
