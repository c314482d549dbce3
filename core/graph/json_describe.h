/* json_describe.h - the one describer of a JSON value for "got ..." in messages, shared by the
 * pipeline loader (pipeline_json*.c) and the pass option readers (pass_options.c); defined in
 * pipeline_json_text.c. Not part of the graph library's interface.
 */
#ifndef PG_JSON_DESCRIBE_H
#define PG_JSON_DESCRIBE_H

#include <cjson/cJSON.h>
#include <stddef.h>

/* "nothing" (NULL), the number (shortest of 15..17 digits that reads back), the string quoted
 * (cut at 40 characters with "..."), true, false, null, "an array", "an object". */
void pj_describe(const cJSON *v, char *buf, size_t n);

#endif
