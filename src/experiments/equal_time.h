/* equal_time.h: the equal-time budget of a method that fits it by paths per pixel (pt, gpt), measured
 * by rendering: the one probe that `restir compare --equal-time` and restir_bench's equal-time tables
 * share, so their spp mean the same thing. The arithmetic is stats.h's equal_time_spp. Must never
 * implement a method. */
#ifndef RESTIR_EXPERIMENTS_EQUAL_TIME_H
#define RESTIR_EXPERIMENTS_EQUAL_TIME_H

#include "methods/renderer.h"
#include "scene/scene.h"

/* The frame time in ms of method m with parameters p (its spp replaced by spp) seen from cam: a new
 * renderer renders frame `frame` as a warm-up (caches, first touch of its buffers), then frame
 * `frame` + 1 from the same camera, which is timed (frame_stats.ms_total, reconstruction included).
 * The frame indices only pick the random streams; a method with state between frames would see a
 * static camera. Uses the renderer's threads; spp >= 1. */
double equal_time_frame_ms(const struct scene *s, const struct method *m, const struct render_params *p,
                           const struct camera *cam, int frame, int spp);

/* The paths per pixel of m (a method without state between frames) that fit budget_ms per frame:
 * equal_time_spp of equal_time_frame_ms at 1 and at 4 spp, whose difference removes the fixed cost of
 * a frame such as gpt's reconstruction. At least 1 (also for a budget that is not a positive
 * finite number). */
int equal_time_spp_for(const struct scene *s, const struct method *m, const struct render_params *p,
                       const struct camera *cam, int frame, double budget_ms);

#endif
