// A plain ODE program for the launcher tests (tests/shell/launcher_*.sh): the box stack of
// stack_scene.h stepped with dWorldStep, ODE's exact world step.
#include "stack_scene.h"

int main(int argc, char** argv) { return stack_scene::run(argc, argv, &dWorldStep); }
