// A plain ODE program for the launcher tests (tests/shell/launcher_quickstep.sh): the box stack
// of stack_scene.h stepped with dWorldQuickStep only, as most games that use ODE do. It imports
// dWorldQuickStep and not dWorldStep.
#include "stack_scene.h"

int main(int argc, char** argv) { return stack_scene::run(argc, argv, &dWorldQuickStep); }
