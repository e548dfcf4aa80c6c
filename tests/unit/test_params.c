/* test_params.c: the settings table (render/params.c): defaults, --set round trips through the
 * spelling render_params_get writes (what summary.json records), BIASED values, and refusals. */
#include <string.h>

#include "core/check.h"
#include "methods/settings.h"
#include "render/params.h"
#include "test_util.h"
#include "methods/gradient/grad_settings.h"
#include "methods/restir_di/di_settings.h"

/* Every key: its value in p, spelled by render_params_get and set again, leaves p unchanged. */
static void expect_round_trip(const struct render_params *p, const char *what)
{
    struct render_params q = *p;
    char msg[RESTIR_MSG_LEN];
    for (size_t i = 0; render_params_key(i); i++) {
        const char *key = render_params_key(i);
        char val[64], assignment[128];
        EXPECT(render_params_get(p, key, val, sizeof(val)) == 0, "%s: %s has no value", what, key);
        snprintf(assignment, sizeof(assignment), "%s=%s", key, val);
        EXPECT(render_params_set(&q, assignment, msg) == 0, "%s: '%s' refused: %s", what, assignment, msg);
    }
    EXPECT(memcmp(p, &q, sizeof(q)) == 0, "%s: settings changed by a round trip", what);
}

int main(void)
{
    char msg[RESTIR_MSG_LEN];
    struct render_params d;
    render_params_defaults(&d);
    /* The table's defaults, spot-checked against the papers' values (DESIGN.md). */
    EXPECT(di_settings_of(&d)->light_candidates == 32 && di_settings_of(&d)->bsdf_candidates == 1,
           "DI candidates 32 + 1");
    EXPECT(d.reuse.confidence_cap == 20.0f, "M cap 20");
    EXPECT(d.reuse.spatial_radius == 30.0f && d.reuse.spatial_normal == 0.5f && d.reuse.spatial_depth == 0.1f,
           "Bitterli test");
    EXPECT(d.reuse.spatial_omega == 0.05f && d.reuse.spatial_beta == 8.0f && d.reuse.spatial_candidates == 32,
           "000 defaults");
    EXPECT(d.spmis.tile == 8 && d.spmis.candidates == 3 && d.spmis.canonical_candidates == 1 &&
               d.spmis.search_steps == 12 && d.spmis.search_growth == 1.25f,
           "004 defaults");
    EXPECT(recon_settings_of(&d)->alpha == 0.2f && recon_settings_of(&d)->mode == RECON_L2 &&
               grad_settings_of(&d)->search == 256,
           "002 defaults");
    EXPECT(d.reuse.mis == RESTIR_MIS_PAIRWISE && d.shift.kind == SHIFT_HYBRID, "pairwise MIS, hybrid shift");
    EXPECT(d.width == 640 && d.height == 360 && d.seed == 1, "640x360, seed 1");
    EXPECT(render_params_validate(&d, msg) == 0, "defaults invalid: %s", msg);
    char biased[256];
    EXPECT(render_params_biased(&d, biased, sizeof(biased)) == 0, "defaults are biased: %s", biased);

    size_t keys = 0;
    while (render_params_key(keys))
        keys++;
    EXPECT(keys > 50, "only %zu keys", keys);
    expect_round_trip(&d, "defaults");

    /* Values a user sets, floats with more digits than %g prints, counts spelled M. */
    struct render_params p = d;
    const char *sets[] = {"spatial.radius=33.3333321", "spatial.omega=0.0123456789", "mis=balance",
                          "shift=replay", "spmis.candidates=M", "spatial.select=compat", "recon=both",
                          "grad.base=shared", "temporal=off", "confidence_cap=7.25"};
    for (size_t k = 0; k < sizeof(sets) / sizeof(sets[0]); k++)
        EXPECT(render_params_set(&p, sets[k], msg) == 0, "'%s' refused: %s", sets[k], msg);
    EXPECT(p.reuse.spatial_omega == (float)0.0123456789, "omega parsed");
    expect_round_trip(&p, "edited");

    /* BIASED values are named, and only those. */
    struct render_params b = d;
    EXPECT(render_params_set_list(&b, "mis=1/M:temporal.ratio_guard=on:recon=l1", msg) == 0, "%s", msg);
    EXPECT(render_params_biased(&b, biased, sizeof(biased)) == 3, "three biased settings, got '%s'", biased);
    EXPECT(strstr(biased, "mis=1/M") && strstr(biased, "temporal.ratio_guard=on") && strstr(biased, "recon=l1"),
           "biased list '%s'", biased);
    EXPECT(render_params_set_list(&b, "recon=both:mis=balance", msg) == 0, "%s", msg);
    EXPECT(render_params_biased(&b, biased, sizeof(biased)) == 1, "recon=both and balance are unbiased: '%s'",
           biased);

    /* Refusals name the key and the value. */
    struct render_params r = d;
    EXPECT(render_params_set(&r, "no.such.key=1", msg) != 0 && strstr(msg, "no.such.key"), "unknown key: %s", msg);
    EXPECT(render_params_set(&r, "spatial.radius=0", msg) != 0 && strstr(msg, "spatial.radius"), "range: %s", msg);
    EXPECT(render_params_set(&r, "spatial.radius=nan", msg) != 0, "NaN accepted");
    EXPECT(render_params_set(&r, "mis=sometimes", msg) != 0 && strstr(msg, "sometimes"), "MIS name: %s", msg);
    EXPECT(render_params_set(&r, "temporal=maybe", msg) != 0 && strstr(msg, "temporal"), "bool: %s", msg);
    EXPECT(memcmp(&r, &d, sizeof(r)) == 0, "a refused --set changed the settings");

    /* Validation reads the table's ranges, also for values set without --set. */
    r = d;
    r.spp = 0;
    EXPECT(render_params_validate(&r, msg) != 0 && strstr(msg, "spp"), "spp 0 valid: %s", msg);
    r = d;
    r.reuse.spatial_radius = NAN;
    EXPECT(render_params_validate(&r, msg) != 0 && strstr(msg, "spatial.radius"), "NaN radius valid: %s", msg);
    r = d;
    r.reuse.spatial_select = (enum spatial_select_mode)7;
    EXPECT(render_params_validate(&r, msg) != 0 && strstr(msg, "spatial.select"), "select 7 valid: %s", msg);
    r = d;
    r.spmis.candidates = 0; /* M: the whole cell */
    EXPECT(render_params_validate(&r, msg) == 0, "spmis.candidates=M invalid: %s", msg);
    return test_finish();
}
