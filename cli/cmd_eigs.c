#include "cli.h"
/* PLACEHOLDER — to be replaced by the real subcommand. */
int cmd_eigs(int argc, char **argv) { (void)argc; (void)argv; return cli_error("eigs: not implemented yet"); }
