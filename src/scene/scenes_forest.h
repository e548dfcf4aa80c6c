/* scenes_forest.h: the built-in scene `forest` (scenes_forest.c), for scenes_builtin.c: its
 * geometry, materials and generated textures through the builder, then its sky once the scene
 * is built. Must never read files. */
#ifndef RESTIR_SCENE_SCENES_FOREST_H
#define RESTIR_SCENE_SCENES_FOREST_H

#include "scene/scene.h"

/* What a grown tree offers to hang things on (the night forest's strings of lamps): its trunk, a
 * tapered cylinder of height `height` standing on base with radius r0 at the foot and r1 at the
 * top, and its branches, each a thin limb (radius 0.06 to 0.025) from branch_root on the trunk's
 * axis along the unit branch_dir for branch_len. Half the leaves fill the crown, an ellipsoid of
 * semi-axes 2.6 m (across) and 2 m (up) centred 0.72 height above base. */
enum { FOREST_GRID = 5, FOREST_TREES = FOREST_GRID * FOREST_GRID, FOREST_BRANCHES = 6 };
struct forest_tree {
    vec3 base;
    float height, r0, r1;
    vec3 branch_root[FOREST_BRANCHES], branch_dir[FOREST_BRANCHES];
    float branch_len[FOREST_BRANCHES];
};

/* The forest's materials, textures, ground and trees (row by row of the FOREST_GRID x FOREST_GRID
 * grid: trees[z * FOREST_GRID + x], x across the path), without camera or sky: what
 * scene_build_forest and the night forest share. */
void scene_forest_grow(struct scene_builder *b, struct forest_tree trees[FOREST_TREES]);
/* Gives s the forest's camera path: a 120-frame walk of 12 m along the path between the trees. */
void scene_forest_walk(struct scene *s);
/* 25 trees with normal-mapped trunks and 3000 alpha-masked leaf cards each on a 400 m ground,
 * its camera and a 120-frame walk along a path between them. */
void scene_build_forest(struct scene_builder *b);
/* Gives the finished scene its generated sky with a sun (its only light). Returns 0, or -1 with
 * msg. */
int scene_light_forest(struct scene *s, char *msg);

#endif
