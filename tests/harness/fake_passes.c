/* fake_passes.c - the fake pass types the compiler's tests share (fake_passes.h). */
#include "fake_passes.h"

pg_result pg_fake_color(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}

pg_result pg_fake_blur(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "src", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "dst", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}

pg_result pg_fake_compose2(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "a", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_read(d, "b", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}

pg_result pg_fake_fill_buffer(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "buf", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    return PG_OK;
}

pg_result pg_fake_storage_write(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "img", PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, PG_FMTCLASS_ANY_COLOR);
    return PG_OK;
}
