/* boiling_filter.h: RTXDI's boiling filter, BIASED by design: in each 8 x 8 pixel group,
 * a reservoir whose weight exceeds the group's mean non-zero weight by a factor 10 / s - 9 (s the
 * strength, 0.2 by default: 41x) is an outlier that would spread into a blotch through reuse, and is
 * dropped. The methods say what a reservoir's weight is (its target x W, the pixel's unshadowed
 * estimate, for DI and paths alike: a DI sample's W alone is per area on a light, per solid angle on
 * the sky, and grows with the light's distance) and empty the ones marked. Trades boiling
 * for a darkening bias (the dropped samples' energy is lost). Must never trace rays. */
#ifndef RESTIR_RENDER_BOILING_FILTER_H
#define RESTIR_RENDER_BOILING_FILTER_H

#define BOILING_FILTER_GROUP 8

/* weight: width x height non-negative weights, row-major (0: an empty reservoir, which does not
 * count toward the mean). Sets weight[i] to -1 for each outlier of its group (a group being the
 * BOILING_FILTER_GROUP x BOILING_FILTER_GROUP pixels from the top-left corner, smaller at the right
 * and bottom edges) and returns their number. strength in (0, 1]; smaller values drop fewer. A
 * non-finite weight counts as an outlier. Runs on the calling thread's OpenMP team. */
long long boiling_filter_mark(float *weight, int width, int height, float strength);

#endif
