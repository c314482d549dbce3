/* fake_passes.h - declare functions of the fake pass types that the compiler's tests
 * (test_graph_compile, test_graph_dump, test_graph_queues) register in their local registries;
 * each test keeps its own type table (names) and the fakes only it uses. No GPU, no create. */
#ifndef PG_FAKE_PASSES_H
#define PG_FAKE_PASSES_H

#include "pass_api.h"

/* writes "color" (colour attachment, float) */
pg_result pg_fake_color(const pg_declare_in *in, pg_pass_decl *d, pg_error *e);
/* reads "src" (sampled in the fragment stage), writes "dst" (colour attachment) */
pg_result pg_fake_blur(const pg_declare_in *in, pg_pass_decl *d, pg_error *e);
/* reads "a" and "b" (sampled in the fragment stage), writes "color" (colour attachment) */
pg_result pg_fake_compose2(const pg_declare_in *in, pg_pass_decl *d, pg_error *e);
/* writes the buffer "buf" (storage, compute) */
pg_result pg_fake_fill_buffer(const pg_declare_in *in, pg_pass_decl *d, pg_error *e);
/* writes the image "img" (storage, compute, any colour format) */
pg_result pg_fake_storage_write(const pg_declare_in *in, pg_pass_decl *d, pg_error *e);

#endif
