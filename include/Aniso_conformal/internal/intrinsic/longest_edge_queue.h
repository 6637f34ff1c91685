// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_INTRINSIC_LONGEST_EDGE_QUEUE_H
#define ANISO_CONFORMAL_INTERNAL_INTRINSIC_LONGEST_EDGE_QUEUE_H

#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <queue>
#include <tuple>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// An edge in a longest-first bisection (refine_background(), make_square_background()): its key (a
// length), then its two ends. Ends, not a halfedge, because the splits renumber nothing but change the
// halfedges of an edge's faces; an entry whose ends are no longer joined was split already.
typedef std::tuple<double, int, int> Edge_key;
typedef std::priority_queue<Edge_key> Longest_edge_queue;

// every edge of `tri` once, keyed by `length(tail, head)` (any callable (int, int) -> double), the
// longest on top
template <typename Length>
Longest_edge_queue longest_edge_queue(const Intrinsic_triangulation& tri, const Length& length)
{
  Longest_edge_queue queue;
  for(int h = 0; h < int(tri.number_of_halfedges()); ++h)
    if(tri.is_edge_representative(h)) queue.emplace(length(tri.tail(h), tri.head(h)), tri.tail(h), tri.head(h));
  return queue;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_INTRINSIC_LONGEST_EDGE_QUEUE_H
