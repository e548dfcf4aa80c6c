/* shift_kind.h: the names of the ReSTIR PT shift mappings (path_shift.h), apart so that the
 * parameter table can parse them without seeing paths. Must never depend on the scene. */
#ifndef RESTIR_RENDER_SHIFT_KIND_H
#define RESTIR_RENDER_SHIFT_KIND_H

enum shift_kind { SHIFT_RECONNECTION = 0, SHIFT_REPLAY, SHIFT_HYBRID };
/* What the hybrid shift's minimum reconnection length shift.distance is measured in: a fraction of
 * the scene's diagonal, scene units, or a fraction of the distance from the camera to the segment's
 * first vertex (the same angular size from every camera distance). */
enum shift_distance_mode { SHIFT_DISTANCE_SCENE = 0, SHIFT_DISTANCE_ABSOLUTE, SHIFT_DISTANCE_RELATIVE };

/* Parses "reconnection", "replay", "hybrid". Returns 0, or -1 for an unknown name. */
int shift_kind_parse(const char *name, enum shift_kind *out);
const char *shift_kind_name(enum shift_kind k);

#endif
