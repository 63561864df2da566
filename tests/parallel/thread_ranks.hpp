#pragma once
// P ranks as P threads of one process, passing messages through shared mailboxes: the
// distributed code paths run under the unit tests without mpirun (tests/fleet runs the real
// MPI build under mpirun).
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "imunoise/parallel/ranks.hpp"

namespace imunoise::test {

class ThreadHub {
 public:
  explicit ThreadHub(int size) : size_(size), boxes_(static_cast<std::size_t>(size)) {}
  int size() const { return size_; }

  void post(int source, int destination, int tag, parallel::Bytes bytes) {
    {
      std::lock_guard lock(mutex_);
      boxes_.at(static_cast<std::size_t>(destination)).push_back({source, tag, std::move(bytes)});
    }
    changed_.notify_all();
  }

  parallel::Bytes take(int me, int source, int tag, int* actual_source) {
    std::unique_lock lock(mutex_);
    auto& box = boxes_.at(static_cast<std::size_t>(me));
    for (;;) {
      for (auto it = box.begin(); it != box.end(); ++it) {
        if (it->tag == tag && (source < 0 || it->source == source)) {
          if (actual_source != nullptr) *actual_source = it->source;
          parallel::Bytes bytes = std::move(it->bytes);
          box.erase(it);
          return bytes;
        }
      }
      changed_.wait(lock);
    }
  }

  // Every rank arrives; rank 0's value and the AND of the flags come back to all.
  std::pair<double, bool> collective(int me, double value, bool ok) {
    std::unique_lock lock(mutex_);
    if (me == 0) pending_value_ = value;
    pending_ok_ = pending_ok_ && ok;
    const long generation = generation_;
    if (++arrived_ == size_) {
      result_ = {pending_value_, pending_ok_};
      arrived_ = 0;
      pending_ok_ = true;
      ++generation_;
      changed_.notify_all();
    } else {
      changed_.wait(lock, [&] { return generation_ != generation; });
    }
    return result_;
  }

 private:
  struct Message {
    int source;
    int tag;
    parallel::Bytes bytes;
  };
  int size_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::deque<Message>> boxes_;
  int arrived_ = 0;
  long generation_ = 0;
  double pending_value_ = 0.0;
  bool pending_ok_ = true;
  std::pair<double, bool> result_{0.0, true};
};

class ThreadRank final : public parallel::Ranks {
 public:
  ThreadRank(ThreadHub& hub, int rank) : hub_(hub), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return hub_.size(); }
  double broadcast(double value) override { return hub_.collective(rank_, value, true).first; }
  bool all_ok(bool ok) override { return hub_.collective(rank_, 0.0, ok).second; }
  void send(int destination, int tag, const parallel::Bytes& bytes) override {
    hub_.post(rank_, destination, tag, bytes);
  }
  parallel::Bytes receive(int source, int tag, int* actual_source) override {
    return hub_.take(rank_, source, tag, actual_source);
  }

 private:
  ThreadHub& hub_;
  int rank_;
};

/// Runs `body` on `size` ranks at once; the exception each rank threw (or null), by rank.
inline std::vector<std::exception_ptr> run_ranks(int size, const std::function<void(parallel::Ranks&)>& body) {
  ThreadHub hub(size);
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(size));
  std::vector<std::thread> threads;
  for (int r = 0; r < size; ++r) {
    threads.emplace_back([&, r] {
      ThreadRank ranks(hub, r);
      try {
        body(ranks);
      } catch (...) {
        errors[static_cast<std::size_t>(r)] = std::current_exception();
      }
    });
  }
  for (auto& t : threads) t.join();
  return errors;
}

}  // namespace imunoise::test
