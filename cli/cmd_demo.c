#include "cli.h"
/* PLACEHOLDER — to be replaced by the real subcommand. */
int cmd_demo(int argc, char **argv) { (void)argc; (void)argv; return cli_error("demo: not implemented yet"); }
