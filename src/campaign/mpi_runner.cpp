// The MPI runner: see mpi_runner.hpp. Protocol (tags below): a worker rank sends `ready`, then receives an
// `item` and answers `result` (or `failed`) until it receives `stop`. The root answers every message with
// the next item or with stop, so each worker has at most one item and one message in flight.
#include "repose/campaign/mpi_runner.hpp"

#include <mpi.h>

#include <array>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "repose/error.hpp"

namespace repose {

namespace {

enum Tag : int { kReady = 1, kResult = 2, kFailed = 3, kItem = 4, kStop = 5 };

// Runs the root's own items on a second thread, one at a time, so that the main thread stays free to serve
// the other ranks.
class LocalWorker {
 public:
  LocalWorker(const WorkRunner::Work& work, std::atomic<std::uint64_t>* progress)
      : work_(work), progress_(progress), thread_([this] { loop(); }) {}
  ~LocalWorker() {
    {
      const std::lock_guard lock(mutex_);
      quit_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  bool busy() const { return busy_; }  // main thread only
  void start(const WorkItem& item) {
    {
      const std::lock_guard lock(mutex_);
      item_ = item;
      busy_ = true;
    }
    changed_.notify_all();
  }
  struct Finished {
    WorkItem item;
    std::string result;
    std::exception_ptr error;
  };
  /// The finished item, if any; waits at most `timeout` for one.
  std::optional<Finished> take(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [this] { return finished_.has_value(); });
    std::optional<Finished> done = std::move(finished_);
    finished_.reset();
    if (done) busy_ = false;
    return done;
  }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
      changed_.wait(lock, [this] { return quit_ || item_.has_value(); });
      if (quit_) return;
      const WorkItem item = *item_;
      item_.reset();
      lock.unlock();
      Finished done{item, {}, nullptr};
      try {
        done.result = work_(item, progress_);
      } catch (...) {
        done.error = std::current_exception();
      }
      lock.lock();
      finished_ = std::move(done);
      changed_.notify_all();
    }
  }

  const WorkRunner::Work& work_;
  std::atomic<std::uint64_t>* progress_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<WorkItem> item_;
  std::optional<Finished> finished_;
  bool busy_ = false;
  bool quit_ = false;
  std::thread thread_;  // last: starts once the rest is initialised
};

class MpiRunner final : public WorkRunner {
 public:
  MpiRunner() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    if (provided < MPI_THREAD_FUNNELED) {
      MPI_Finalize();
      throw Error("the MPI library does not support MPI_THREAD_FUNNELED");
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
    MPI_Comm node;
    MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &local_);
    MPI_Comm_free(&node);
  }
  ~MpiRunner() override {
    MPI_Comm_free(&comm_);
    MPI_Finalize();
  }
  MpiRunner(const MpiRunner&) = delete;
  MpiRunner& operator=(const MpiRunner&) = delete;

  int rank() const override { return rank_; }
  int ranks() const override { return size_; }
  int ranks_on_this_node() const override { return local_; }

  std::string broadcast(const std::string& value) override {
    std::uint64_t size = value.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm_);
    std::string text = rank_ == 0 ? value : std::string(size, '\0');
    MPI_Bcast(text.data(), checked_count(size), MPI_CHAR, 0, comm_);
    return text;
  }

  void run(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
           std::atomic<std::uint64_t>* progress) override {
    std::exception_ptr failure;
    if (rank_ == 0)
      failure = serve(items, work, absorb, progress);
    else
      work_loop(work);
    // Every rank waits here until the root is done, so that no message of a later run() can reach the root
    // while it still serves this one, and learns whether the run succeeded: 0, or the exit code of the
    // root's error (2 for repose::Error, as the root reports it; 1 otherwise).
    int code = failure ? exit_code_of(failure) : 0;
    MPI_Bcast(&code, 1, MPI_INT, 0, comm_);
    if (failure) std::rethrow_exception(failure);
    if (code != 0) throw RootFailed{code};
  }

 private:
  static int exit_code_of(const std::exception_ptr& failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const Error&) {
      return 2;
    } catch (...) {
      return 1;
    }
  }
  static int checked_count(std::uint64_t size) {
    if (size > static_cast<std::uint64_t>(INT_MAX)) throw Error("MPI message larger than 2 GiB");
    return static_cast<int>(size);
  }
  void send_text(int to, int tag, const std::string& text) {
    MPI_Send(text.data(), checked_count(text.size()), MPI_CHAR, to, tag, comm_);
  }
  std::string receive_text(const MPI_Status& status) {
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    std::string text(static_cast<std::size_t>(count), '\0');
    MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, comm_, MPI_STATUS_IGNORE);
    return text;
  }

  void work_loop(const Work& work) {
    send_text(0, kReady, "");
    for (;;) {
      MPI_Status status;
      MPI_Probe(0, MPI_ANY_TAG, comm_, &status);
      if (status.MPI_TAG == kStop) {
        receive_text(status);
        return;
      }
      std::array<std::uint64_t, 3> message{};
      MPI_Recv(message.data(), 3, MPI_UINT64_T, 0, kItem, comm_, MPI_STATUS_IGNORE);
      const WorkItem item{static_cast<std::uint32_t>(message[0]), {message[1], message[2]}};
      try {
        send_text(0, kResult, work(item, nullptr));
      } catch (const std::exception& e) {
        send_text(0, kFailed, e.what());
      }
    }
  }

  // Returns the first error (work on any rank, or absorb), after every rank has stopped.
  std::exception_ptr serve(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
                           std::atomic<std::uint64_t>* progress) {
    std::size_t next = 0;
    std::exception_ptr failure;  // the first error; after it no new items are handed out
    const auto next_item = [&]() -> std::optional<WorkItem> {
      if (failure || next >= items.size()) return std::nullopt;
      return items[next++];
    };
    const auto take_result = [&](const WorkItem& item, const std::string& result) {
      if (failure) return;
      try {
        absorb(item, result);
      } catch (...) {
        failure = std::current_exception();
      }
    };
    std::vector<std::optional<WorkItem>> running(static_cast<std::size_t>(size_));
    int workers = size_ - 1;  // ranks not yet told to stop
    LocalWorker local(work, progress);
    if (const auto item = next_item()) local.start(*item);
    // Bounded: every pass either takes a message or a finished local item, or waits; each rank sends one
    // message per item plus one, and the items are finite.
    while (workers > 0 || local.busy()) {
      int flag = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm_, &flag, &status);
      if (flag) {
        const int from = status.MPI_SOURCE;
        const std::string text = receive_text(status);
        auto& slot = running[static_cast<std::size_t>(from)];
        if (status.MPI_TAG == kResult && slot) {
          take_result(*slot, text);
          if (progress) *progress += slot->drops.size();
        } else if (status.MPI_TAG == kFailed && !failure) {
          failure = std::make_exception_ptr(Error("rank " + std::to_string(from) + ": " + text));
        }
        slot.reset();
        if (const auto item = next_item()) {
          const std::array<std::uint64_t, 3> message{item->particle, item->drops.begin, item->drops.end};
          MPI_Send(message.data(), 3, MPI_UINT64_T, from, kItem, comm_);
          slot = item;
        } else {
          send_text(from, kStop, "");
          --workers;
        }
      }
      // Wait for the local item only when no message is pending (a short wait doubles as the poll interval).
      if (local.busy()) {
        if (auto done = local.take(std::chrono::milliseconds(flag ? 0 : 1))) {
          if (done->error && !failure) failure = done->error;
          if (!done->error) take_result(done->item, done->result);
          if (const auto item = next_item()) local.start(*item);
        }
      } else if (!flag) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
    return failure;
  }

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  int size_ = 1;
  int local_ = 1;
};

}  // namespace

std::unique_ptr<WorkRunner> make_mpi_runner() { return std::make_unique<MpiRunner>(); }

}  // namespace repose
