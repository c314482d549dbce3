#ifndef PG_COMMANDS_H
#define PG_COMMANDS_H

#include <stdio.h>

#include "render_session.h"

int pg_cmd_render(int argc, char **argv);
int pg_cmd_view(int argc, char **argv);
int pg_cmd_devices(int argc, char **argv);
int pg_cmd_compare(int argc, char **argv);
int pg_cmd_dump(int argc, char **argv);
int pg_cmd_bench(int argc, char **argv);
int pg_cmd_bench_merge(int argc, char **argv);
int pg_cmd_lights_table(int argc, char **argv);
void pg_print_explain(const pg_session *s, FILE *f);

#endif
