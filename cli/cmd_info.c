#include "cli.h"
/* PLACEHOLDER — to be replaced by the real subcommand. */
int cmd_info(int argc, char **argv) { (void)argc; (void)argv; return cli_error("info: not implemented yet"); }
