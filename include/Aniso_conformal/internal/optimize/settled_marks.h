// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_OPTIMIZE_SETTLED_MARKS_H
#define ANISO_CONFORMAL_INTERNAL_OPTIMIZE_SETTLED_MARKS_H

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// The bookkeeping that lets the passes of the surface optimiser (surface_optimizer.h) skip what would
// not change. A vertex visit depends only on the vertex's one-ring (the positions and metrics of the
// vertex and its neighbours, the faces around it), an edge's flip test only on its quad's four vertices;
// so a vertex that a pass left where it was is skipped by that pass while neither it nor a neighbour has
// changed since, and an edge that a flip test kept is skipped while its four vertices have not. The output
// is the one of visiting everything, bit for bit.
//
// One clock: every change and every visit or test that changes nothing takes the next tick. Per vertex,
// the tick of its last change (a move, or a flip of an edge of its faces or opposite it); per kind of
// vertex pass and vertex, the tick of the last visit that left it in place (0: none); per edge, the tick
// of its last flip test that kept it (0: none).
class Settled_marks {
public:
  // the vertex passes told apart
  enum Pass : std::size_t { RELOCATION, RELAXED_RELOCATION, ANGLE, kinds };

  void reset(std::size_t vertices, std::size_t edges)
  {
    m_clock = 1;
    m_changed.assign(vertices, 1);
    for(auto& settled : m_settled) settled.assign(vertices, 0);
    m_edge_settled.assign(edges, 0);
  }
  // forgets the visits of pass `kind` (its parameters changed: another pass)
  void forget(std::size_t kind) { std::fill(m_settled[kind].begin(), m_settled[kind].end(), 0); }
  void changed(std::size_t v) { m_changed[v] = ++m_clock; }
  void changed(std::initializer_list<std::size_t> vs)
  {
    for(std::size_t v : vs) changed(v);
  }

  // whether pass `kind` may skip vertex `v` with the neighbours `ring` (a range of vertex indices)
  template <typename Neighbours>
  bool settled(std::size_t kind, std::size_t v, const Neighbours& ring) const
  {
    const std::uint64_t t = m_settled[kind][v];
    if(t == 0 || m_changed[v] >= t) return false;
    for(std::size_t u : ring)
      if(m_changed[u] >= t) return false;
    return true;
  }
  void left_in_place(std::size_t kind, std::size_t v) { m_settled[kind][v] = ++m_clock; }

  // whether the flip test of edge `e` may be skipped, its quad being (a, b, c, d)
  bool edge_settled(std::size_t e, std::size_t a, std::size_t b, std::size_t c, std::size_t d) const
  {
    const std::uint64_t t = m_edge_settled[e];
    return t != 0 && std::max({m_changed[a], m_changed[b], m_changed[c], m_changed[d]}) < t;
  }
  void edge_tested(std::size_t e) { m_edge_settled[e] = ++m_clock; }

private:
  std::uint64_t m_clock = 0;
  std::vector<std::uint64_t> m_changed;
  std::array<std::vector<std::uint64_t>, kinds> m_settled;
  std::vector<std::uint64_t> m_edge_settled;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_OPTIMIZE_SETTLED_MARKS_H
