// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_EMBEDDING_MEMO_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_EMBEDDING_MEMO_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <cstdint>
#include <exception>
#include <optional>

namespace Aniso_conformal {
namespace internal {

// The last conformal embedding of one run_pipeline() call, by the background it was computed from.
//
// The pipeline runs up to four times on one background (remesh_in_domain.h, run_pipeline(): the runs
// that follow the creases, the run with the corners only, the run without feature sites; with boundary
// loops, the run with the next seed), and stage 2 gives most of them the same background, edge lengths
// and all: the embedding, a function of that background and of the named parameters alone (which the
// runs share), was solved again each time. CGAL's cheese (genus 133) solved the same failing hyperbolic
// embedding four times, the same residuals at every Newton iteration from the second run on. The memo
// keeps the last embedding, or its failure (a Remeshing_failure), with the background's fingerprint
// (Intrinsic_triangulation::fingerprint(), a 64-bit hash of everything the embedding reads): a run whose
// background has that fingerprint gets the embedding and the background after it (the embeddings flip
// edges) without solving, or the same exception. One entry: the runs that share a background follow each
// other. Other exceptions (Cancelled, Invalid_input, Internal_error) are not kept.
template <typename Domain>
class Embedding_memo {
public:
  typedef typename Domain::Embedding Embedding;

  // false: a new embedding is not kept (the run is the last to use this background)
  bool keep = true;

  // the embedding of `itri` (Domain::embed(itri, np)), `itri` as the embedding leaves it; `reused` set
  // to whether it came from the memo
  template <typename NamedParameters>
  Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np, bool& reused)
  {
    const std::uint64_t key = itri.fingerprint();
    reused = m_valid && key == m_key;
    if(reused) {
      if(m_failure) std::rethrow_exception(m_failure);
      itri = *m_itri;
      return *m_embedding;
    }
    m_valid = false;
    m_itri.reset();
    m_embedding.reset();
    m_failure = nullptr;
    if(!keep) return Domain::embed(itri, np);
    try {
      Embedding emb = Domain::embed(itri, np);
      m_itri.emplace(itri);
      m_embedding.emplace(emb);
      m_key = key;
      m_valid = true;
      return emb;
    } catch(const Remeshing_failure&) {
      m_failure = std::current_exception();
      m_key = key;
      m_valid = true;
      throw;
    }
  }

private:
  bool m_valid = false;
  std::uint64_t m_key = 0;
  std::optional<Intrinsic_triangulation> m_itri;  // after the embedding
  std::optional<Embedding> m_embedding;
  std::exception_ptr m_failure;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_EMBEDDING_MEMO_H
