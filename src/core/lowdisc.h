/* lowdisc.h: low-discrepancy point sets: Roberts' R2 sequence mapped to the unit disk, the
 * candidate offsets of compatibility-guided neighbor selection (000 Sec. 5).
 * Must never depend on scenes or render passes. */
#ifndef RESTIR_CORE_LOWDISC_H
#define RESTIR_CORE_LOWDISC_H

/* Number of precomputed disk offsets (000 Sec. 5 uses 8192). */
#define R2_DISK_OFFSETS 8192

/* Writes n points of the R2 sequence (Roberts 2018: frac(0.5 + i / g), frac(0.5 + i / g^2), g the
 * plastic number) mapped through the concentric disk map to xy[2i], xy[2i+1]. */
void r2_disk_offsets(int n, float *xy);

/* The first R2_DISK_OFFSETS of those points (xy pairs), computed on the first call and shared by
 * every caller for the life of the process (never freed). Safe to call from any thread. */
const float *r2_disk_table(void);

#endif
