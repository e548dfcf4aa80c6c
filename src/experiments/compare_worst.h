/* compare_worst.h: where a gradient method's worst pairs are, as an image beside compare's outputs
 * (compare_worst.c). Must never render or measure anything but the pairs it is given. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_WORST_H
#define RESTIR_EXPERIMENTS_COMPARE_WORST_H

/* The file name's ending after the row's folder name: DIR/FOLDER_grad_worst1.png. */
#define COMPARE_WORST_SUFFIX "_grad_worst1.png"

/* Writes out_dir/<dir>COMPARE_WORST_SUFFIX: the reference (ref, RGB) tone-mapped as compare's PNGs and dimmed to
 * a third, with the pixels a of the pairs restir_metrics_gradient_worst_pairs puts in the worst `fraction` of the
 * gradient relMSE painted: the x pair (a, a + x) red, the y pair (a, a + y) cyan, both white. dx, dy: the
 * estimated forward differences, 3 floats per pixel each. Returns 0, or -1 with msg. */
int compare_write_worst_pairs(const char *out_dir, const char *dir, const float *dx, const float *dy, const float *ref,
                              int width, int height, double fraction, char *msg);

#endif
