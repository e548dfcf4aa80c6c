/* lights.h: emitter sampling through the scene's emitter table (scene/scene_lights.h): a triangle
 * chosen by power (or by importance down the emitter BVH), a point on it uniform in area (or in
 * solid angle), its emission. Must never depend on render passes. */
#ifndef RESTIR_SHADING_LIGHTS_H
#define RESTIR_SHADING_LIGHTS_H

#include "scene/scene.h"
#include "scene/scene_lights.h" /* lights_emitter_power: the scene builds the table with it */

/* A point on a light. Densities are in area measure on the light; lights_pdf_solid_angle converts. */
struct light_sample {
    int tri;        /* triangle index of the emitter */
    float b1, b2;   /* barycentrics of the point on the triangle */
    vec3 p;         /* point on the light */
    vec3 n;         /* light's geometric (emitting) normal */
    vec3 Le;        /* emitted radiance toward the front side */
    float pdf_area; /* density of choosing this point, area measure */
};

/* Samples a point on the emitters from three uniforms. Returns 0 when the scene has no lights. */
int lights_sample(const struct scene *s, float u_select, float u1, float u2, struct light_sample *ls);
/* How next-event estimation picks an emitter: by power from the scene's alias table (the same
 * everywhere), or by importance at the shading point down the emitter BVH (light_tree.h). */
enum light_selection { LIGHT_SELECT_POWER = 0, LIGHT_SELECT_BVH };
/* How it then picks a point on the emitting triangle: uniform in its area; uniform in the solid
 * angle it subtends (Arvo 1995; a triangle that is half of a rectangle (scene_lights.c) draws the
 * whole rectangle, Urena et al. 2013; area where the solid angle is below LIGHTS_SOLID_ANGLE_MIN); or
 * auto: solid angle only where the area density spreads over the emitter by LIGHTS_AUTO_SPREAD, the
 * rule per emitter and receiver that lights_sample_at spells out. */
enum light_sampling { LIGHT_SAMPLING_AREA = 0, LIGHT_SAMPLING_SOLID_ANGLE, LIGHT_SAMPLING_AUTO };
/* How a path walk samples the environment: its map's distribution (scene->env_sampler), or the
 * MIS-compensated one (scene->env_sampler_compensated, env_light.h; the map's where that is empty),
 * unbiased only next to BSDF sampling, which every path walk does. */
enum light_env_sampling { LIGHT_ENV_MAP = 0, LIGHT_ENV_COMPENSATED };
/* The choices: {power, area, map} is what lights_sample does (with the scene's env_sampler). */
struct light_choice {
    enum light_selection select;
    enum light_sampling point;
    enum light_env_sampling env;
};
/* The strategy lights_sample implements: by power from the alias table, uniform in area. */
#define LIGHT_CHOICE_POWER_AREA ((struct light_choice){LIGHT_SELECT_POWER, LIGHT_SAMPLING_AREA, LIGHT_ENV_MAP})

/* lights_sample for a shading point x with unit normal n (its side does not matter), by the
 * strategy `choice`: the emitter by choice.select, then the point uniform in the solid angle the
 * emitter subtends from x where choice.point says so, else uniform in its area:
 *  - solid-angle: where the emitter's area over the squared distance of its centre and then its solid
 *    angle are both at least LIGHTS_SOLID_ANGLE_MIN;
 *  - auto: where (d_max / d_min)^2 >= LIGHTS_AUTO_SPREAD for its farthest and closest points from x
 *    (for a triangle d_min bounded below) and its solid angle is at least LIGHTS_SOLID_ANGLE_MIN.
 * An emitter that is half of a rectangle applies the rule to the rectangle and draws the point over
 * the whole of it (spherical_rect.h), with probability P(half 0) + P(half 1) for the rectangle;
 * others use Arvo's spherical triangle (spherical_triangle.h). Receivers within 1e-4 of the size of
 * the emitter's plane use area sampling. ls->pdf_area is the area density that gives the solid-angle
 * density of the choice under lights_pdf_solid_angle (P / omega when by solid angle). Returns 0 when
 * no emitter is chosen (none in the scene, or by BVH none that can light x). */
int lights_sample_at(const struct scene *s, struct light_choice choice, vec3 x, vec3 n, float u_select, float u1,
                     float u2, struct light_sample *ls);
/* The solid-angle density with which lights_sample_at(s, choice, x, n, ...) produces a point of
 * triangle tri at distance dist from x, where the triangle's normal and the direction make cosine
 * cos_l: the same rules for the same x, n and tri. 0 when tri is not an emitter. */
float lights_pdf_at(const struct scene *s, struct light_choice choice, vec3 x, vec3 n, int tri, float dist,
                    float cos_l);
/* Below this solid angle (sr, a cone of about 0.08 rad half-angle) the sampler uses area sampling:
 * there the area density varies across the triangle by a few percent only, so the spherical form's
 * trigonometry would cost without lowering variance (measured in docs/BENCHMARKS.md: at 3e-4 sr the
 * furnace's triangles were all sampled spherically, 1.6x the time at the same error). */
#define LIGHTS_SOLID_ANGLE_MIN 0.02
/* lights.sample=auto's threshold on (d_max / d_min)^2: the area density's factor cos / d^2 = h / d^3
 * varies by 8x over the emitter where it is reached. Area sampling's excess variance over solid
 * angle's (for a uniform integrand) is about 0.1 ((d_max / d_min)^2 - 1) (computed for a square), and
 * a solid-angle sample costs about 100 ns more (docs/BENCHMARKS.md, "spherical rectangles, float
 * spherical triangles and lights.sample=auto": thresholds 2 and 4 measured on box, cornell and
 * big_light). */
#define LIGHTS_AUTO_SPREAD 4.0f
/* Area density of producing the point on triangle tri (0 when tri is not an emitter). */
float lights_pdf_area(const struct scene *s, int tri);
/* Point b1, b2 of emitter em (p = v0 + b1 e1 + b2 e2) with its normal, radiance and density:
 * the one formula light sampling, lights_point and ReSTIR DI's light pool all use. */
void lights_emitter_point(const struct scene *s, const struct emitter *em, float b1, float b2,
                          struct light_sample *ls);
/* Fills ls->p, n, Le, pdf_area from tri and barycentrics. */
void lights_point(const struct scene *s, int tri, float b1, float b2, struct light_sample *ls);
/* Radiance leaving emitter triangle tri at barycentrics b1, b2 toward direction w_out (zero on its
 * back side). */
vec3 lights_radiance(const struct scene *s, int tri, float b1, float b2, vec3 w_out);
/* Converts an area density at a light point to solid angle as seen from x. */
float lights_pdf_solid_angle(float pdf_area, vec3 x, vec3 light_p, vec3 light_n);

#endif
