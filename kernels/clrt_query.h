/* clrt_query.h - the scene-wide ray queries that the tracer, shading and
 * the layers ask, per lane:
 *   closest_intersection(O, D, tmin, tmax, self, active, scene, &t,
 *     &tests): the id of the nearest primitive hit in (tmin, tmax), or -1,
 *     and its distance; equal distances go to the lower id; for the lanes of
 *     `active` (the others may answer -1 and infinity: a block walk does
 *     not walk their rays);
 *   any_intersection(O, D, tmin, tmax, self, active, scene, &tests): whether
 *     anything blocks (tmin, tmax), for the lanes of `active` (shadow rays:
 *     the search may stop at the first blocker).
 * `self` is the primitive the ray starts on; `tests` counts primitive tests
 * per lane (the ray counters). Two implementations give the same answers,
 * lane by lane: clrt_query_all.h tests every primitive, clrt_bvh.h walks
 * the hierarchy (-DCLRT_BVH). Each defines them only in its own builds, so
 * including both here is what picks one, and every caller includes this
 * file and nothing under it. */
#ifndef CLRT_QUERY_H
#define CLRT_QUERY_H

#include "clrt_bvh.h"
#include "clrt_query_all.h"

#endif /* CLRT_QUERY_H */
