#pragma once
// The message passing that the distributed computations need (one record sliced over ranks,
// a fleet of files handed out), as an interface: the executable implements it over MPI, the
// library never links MPI, and a single process is one rank. Every call is collective or
// point to point as in MPI: all ranks call broadcast and all_ok together.
#include <cstdint>
#include <functional>
#include <vector>

namespace imunoise::parallel {

using Bytes = std::vector<std::uint8_t>;

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Rank 0's value on every rank.
  virtual double broadcast(double value) = 0;
  /// True on every rank when `ok` is true on every rank: a collective error check, so that a
  /// rank that failed and the ranks waiting for it all leave together instead of hanging.
  virtual bool all_ok(bool ok) = 0;
  /// Point-to-point messages of any length; `source` -1 is any rank.
  virtual void send(int destination, int tag, const Bytes& bytes) = 0;
  virtual Bytes receive(int source, int tag, int* actual_source = nullptr) = 0;
};

/// A plain run: one rank, rank 0. Messages have nowhere to go (a logic error if sent).
class SingleRank final : public Ranks {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double broadcast(double value) override { return value; }
  bool all_ok(bool ok) override { return ok; }
  void send(int destination, int tag, const Bytes& bytes) override;
  Bytes receive(int source, int tag, int* actual_source) override;
};

/// Binary-tree reduction: at level s, rank r (r % 2s == 0) receives the image of rank r + s
/// (the data that follows its own) and hands it to absorb(); rank r % 2s == s sends encode()
/// to rank r - s and leaves. log2(P) levels; rank 0 ends with everything absorbed.
void tree_merge(Ranks& ranks, const std::function<Bytes()>& encode,
                const std::function<void(const Bytes&)>& absorb);

}  // namespace imunoise::parallel
