/* aov_channels.h: the first-hit layers' channels (CLPT_AOVS; docs/aovs.md), as a job's results and
 * a pass's per-pixel sums lay them out (film_aov.cl) and the host reads them (render/film.h).
 * Valid C++ and OpenCL C. */
#ifndef CLPT_AOV_CHANNELS_H
#define CLPT_AOV_CHANNELS_H

#define CLPT_AOV_ALBEDO 0u   /* albedo R, G, B: [0, 1] */
#define CLPT_AOV_NORMAL 3u   /* shading normal X, Y, Z: world space, unit (0 for a miss) */
#define CLPT_AOV_DEPTH 6u    /* distance along the camera ray to its first hit, world units (0 for a miss) */
#define CLPT_AOV_CHANNELS 7u /* floats per job result and per pixel sum */

#endif
