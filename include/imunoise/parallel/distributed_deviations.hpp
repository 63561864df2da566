#pragma once
// One record larger than a machine (`dev --mpi`, `fit --mpi`): each rank reads its own slice
// of the file, accumulates the mergeable Allan-family sums (imunoise/difference_accumulator.hpp)
// and the partial sums are merged in a binary tree (ranks.hpp).
//
// Raw binary files: positioned reads, rank r of P reads the rate records [r N / P, (r+1) N / P)
// (angle input: the phase samples [r (N-1) / P, (r+1) (N-1) / P], sharing the boundary sample),
// integrates them from the rate offset rank 0 computed on the first 2^20 samples (the serial
// loader's offset), so the pieces join exactly as one pass. Text files cannot be cut at a
// sample without reading them: rank 0 loads the whole file and sends each rank its slice (the
// computation is distributed, the memory on rank 0 is the serial one).
//
// Memory per rank: its slice of phase (8 bytes per sample, held while each estimator is pushed)
// plus, for the estimator being merged, the edges of its accumulator (2 min(L, W) doubles,
// W = the largest stencil, 2 m_max for oadev) and at a merge of level l the partner's image, its
// decoded copy and the cross-term buffer: at most 8 (L + 1) + 64 min(2^l L, W) bytes
// (docs/scale.md).
#include <cstddef>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/parallel/ranks.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::parallel {

struct DistributedCurves {
  bool root = false;                          ///< rank 0: the only rank holding the results
  Record record;                              ///< description (phase_si empty); valid on rank 0
  std::size_t n_phase = 0;                    ///< phase samples of the whole record
  std::vector<std::vector<DevPoint>> curves;  ///< per estimator, SI, no confidence (rank 0)
  /// Rank 0's own slice of the phase (SI), the first ~n_phase/P points: enough to identify the
  /// noise type at all but the longest taus; kept, not gathered, so memory stays bounded.
  std::vector<double> root_phase_si;
};

/// The estimators a distributed run can compute (mergeable): adev oadev mdev tdev hdev ohdev.
bool is_mergeable(Estimator estimator);

/// Reads `input` sliced over the ranks and computes each estimator at the factors `grid` gives
/// (estimator_averaging_factors). On one rank it is a plain, serial computation. InputError
/// (with the file and record) on every rank when any rank's slice is bad; never hangs.
DistributedCurves distributed_deviations(Ranks& ranks, const load::LoadOptions& input,
                                         const std::vector<Estimator>& estimators, const TauGrid& grid);

}  // namespace imunoise::parallel
