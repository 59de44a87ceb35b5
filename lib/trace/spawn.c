/* Where a ray spawned at a hit starts: the one rule the renderer uses for
 * shadow, reflected and refracted rays, public so a caller's own integrator
 * (and the self-intersection tests) leave surfaces the same way. The rule
 * and its reasons are in trace/spawn.h, which shade inlines. */
#include "trace/spawn.h"
#include "trace/trace_context.h"

HR_API hr_vec3 hr_hit_spawn_origin(const hr_hit *hit, hr_vec3 side) { return hri_hit_spawn_origin(hit, side); }
