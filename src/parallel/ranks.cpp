#include "imunoise/parallel/ranks.hpp"

#include <stdexcept>

namespace imunoise::parallel {

void SingleRank::send(int, int, const Bytes&) {
  throw std::logic_error("a single-rank run has no other rank to send to");
}

Bytes SingleRank::receive(int, int, int*) {
  throw std::logic_error("a single-rank run has no other rank to receive from");
}

void tree_merge(Ranks& ranks, const std::function<Bytes()>& encode,
                const std::function<void(const Bytes&)>& absorb) {
  constexpr int kTag = 17;
  const int rank = ranks.rank(), size = ranks.size();
  for (int step = 1; step < size; step *= 2) {
    if (rank % (2 * step) == step) {
      ranks.send(rank - step, kTag, encode());
      return;
    }
    if (rank % (2 * step) == 0 && rank + step < size) absorb(ranks.receive(rank + step, kTag));
  }
}

}  // namespace imunoise::parallel
