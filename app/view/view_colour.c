/* view_colour.c - `passgraph view`: colour management (OpenColorIO config, display and view
 * lists, the settings every session gets) and its panel. */
#include "view.h"

/* ---------------------------------------------------------------- colour (OpenColorIO) */

static void colour_settings(viewer *v)
{
    v->n_settings = 0;
    if (v->app.opt.ocio_config) v->settings[v->n_settings++] = (pg_param_override){"ocio.config", v->ocio_path};
    if (v->colour_chosen && v->display[0])
        v->settings[v->n_settings++] = (pg_param_override){"ocio.display", v->display};
    if (v->colour_chosen && v->ocio_view[0])
        v->settings[v->n_settings++] = (pg_param_override){"ocio.view", v->ocio_view};
}

/* Opens the config for its lists; the display and view start from the command line, else the
 * config's defaults. A config that does not load is shown in the window (the display pass reports
 * it too). */
void colour_init(viewer *v)
{
    pg_ocio_resolve_path(v->app.opt.ocio_config, v->ocio_path, sizeof v->ocio_path);
    v->colour_chosen = v->app.opt.display || v->app.opt.ocio_view;
    pg_error err = {0};
    if (pg_ocio_open(v->ocio_path, &v->ocio, &err)) {
        snprintf(v->ocio_error, sizeof v->ocio_error, "%s", err.msg);
        v->ocio = NULL;
    } else if (pg_ocio_resolve(v->ocio, v->app.opt.display, v->app.opt.ocio_view, v->display, sizeof v->display,
                               v->ocio_view, sizeof v->ocio_view, &err)) {
        snprintf(v->ocio_error, sizeof v->ocio_error, "%s", err.msg);
    }
    if (!v->display[0] && v->app.opt.display) pg_strlcpy(v->display, v->app.opt.display, sizeof v->display);
    if (!v->ocio_view[0] && v->app.opt.ocio_view) pg_strlcpy(v->ocio_view, v->app.opt.ocio_view, sizeof v->ocio_view);
    colour_settings(v);
}

/* Picks a display (its default view unless `view` is one of its views) or a view; reloads. */
pg_result colour_choose(viewer *v, const char *display, const char *view, pg_error *err)
{
    if (!v->ocio) return pg_fail(err, PG_ERR_INVALID_ARG, "%s", v->ocio_error[0] ? v->ocio_error : "no OCIO config");
    const char *d = display ? display : v->display;
    const char *w = view ? view : (display && !pg_ocio_has_view(v->ocio, display, v->ocio_view) ? NULL : v->ocio_view);
    char nd[sizeof v->display], nv[sizeof v->ocio_view];
    pg_result r = pg_ocio_resolve(v->ocio, d, w, nd, sizeof nd, nv, sizeof nv, err);
    if (r) return r;
    if (strcmp(nd, v->display) || strcmp(nv, v->ocio_view)) {
        pg_strlcpy(v->display, nd, sizeof v->display);
        pg_strlcpy(v->ocio_view, nv, sizeof v->ocio_view);
        v->colour_chosen = true;
        colour_settings(v);
        v->reload = true;
    }
    return PG_OK;
}

void colour_ui(viewer *v)
{
    if (!pg_ui_header("Colour (OpenColorIO)", true)) return;
    if (!v->ocio) {
        pg_ui_text_colored(0xff5050ff, "OCIO config:");
        pg_ui_text_wrapped(v->ocio_error);
        return;
    }
    pg_ui_text_wrapped(pg_ocio_config_path(v->ocio));
    const char *items[32];
    int n = 0, cur = 0;
    for (uint32_t i = 0; i < pg_ocio_num_displays(v->ocio) && n < 32; i++) {
        items[n] = pg_ocio_display(v->ocio, i);
        if (items[n] && !strcmp(items[n], v->display)) cur = n;
        if (items[n]) n++;
    }
    pg_error err = {0};
    if (pg_ui_combo("display", &cur, items, n)) colour_choose(v, items[cur], NULL, &err);
    n = 0;
    cur = 0;
    for (uint32_t i = 0; i < pg_ocio_num_views(v->ocio, v->display) && n < 32; i++) {
        items[n] = pg_ocio_view(v->ocio, v->display, i);
        if (items[n] && !strcmp(items[n], v->ocio_view)) cur = n;
        if (items[n]) n++;
    }
    if (pg_ui_combo("view", &cur, items, n)) colour_choose(v, NULL, items[cur], &err);
    pg_ui_tooltip("the OCIO view transform from scene-linear to the display (a new session is made)");
    const pg_pipeline *pl = v->session ? v->session->pipeline : NULL;
    const pg_param *ex = pl ? pg_pipeline_find_param(pl, "exposure") : NULL;
    if (ex && ex->type == PG_PARAM_FLOAT) {
        float stops = ex->number > 0 ? (float)log2(ex->number) : 0.0f;
        if (pg_ui_slider_float("exposure EV", &stops, -10.0f, 10.0f, "%+.2f", false)) {
            char val[PG_NAME_MAX];
            snprintf(val, sizeof val, "%.9g", exp2((double)stops));
            set_override(v, "exposure", val);
            v->reload = true;
        }
        pg_ui_tooltip("the pipeline parameter 'exposure' (x 2^stops), a scene-linear multiply before the view");
    }
}
