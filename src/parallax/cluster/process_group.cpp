#include "parallax/cluster/process_group.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <thread>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/parallel.h"

namespace parallax::cluster {

PeerFailed::PeerFailed(Failure failure)
    : std::runtime_error("rank " + std::to_string(failure.rank) + " failed: " + failure.message),
      failure_(std::move(failure)) {}

void ProcessGroup::checkpoint() {
  if (std::optional<Failure> failure = agree(std::nullopt)) throw PeerFailed(std::move(*failure));
}

namespace {

class SingleProcess final : public ProcessGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::optional<Failure> agree(const std::optional<Failure>& mine) override { return mine; }
  void mergeToRoot(std::span<uint8_t>) override {}
  void sumOnAll(std::span<uint64_t>) override {}
  double maxOnAll(double value) override { return value; }
};

// MPI counts are ints: large buffers go in pieces of 1 GiB.
constexpr size_t kPiece = size_t(1) << 30;

class MpiWorld final : public ProcessGroup {
 public:
  MpiWorld() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::optional<Failure> agree(const std::optional<Failure>& mine) override {
    const int myFailure = mine ? rank_ : INT_MAX;
    int lowest = INT_MAX;
    // Ranks arrive here at different times (one frame's bands, or frames, cost unequally). A
    // blocking MPI call spins on a core while it waits, taking it from ranks still rendering
    // on the same machine, so the wait is a test every millisecond that sleeps in between.
    MPI_Request request;
    MPI_Iallreduce(&myFailure, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
    for (int done = 0;;) {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (lowest == INT_MAX) return std::nullopt;
    // The lowest failing rank tells everyone its exit code and message.
    int header[2] = {0, 0};
    std::string message;
    if (lowest == rank_) {
      header[0] = mine->exitCode;
      header[1] = int(std::min<size_t>(mine->message.size(), 1 << 20));
      message = mine->message.substr(0, size_t(header[1]));
    }
    MPI_Bcast(header, 2, MPI_INT, lowest, MPI_COMM_WORLD);
    message.resize(size_t(header[1]));
    if (header[1] > 0) MPI_Bcast(message.data(), header[1], MPI_CHAR, lowest, MPI_COMM_WORLD);
    return Failure{lowest, header[0], message};
  }

  void mergeToRoot(std::span<uint8_t> bytes) override {
    checkpoint();
    for (size_t at = 0; at < bytes.size(); at += kPiece) {
      const int count = int(std::min(kPiece, bytes.size() - at));
      uint8_t* data = bytes.data() + at;
      MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : data, data, count, MPI_BYTE, MPI_BOR, 0,
                 MPI_COMM_WORLD);
    }
  }

  void sumOnAll(std::span<uint64_t> values) override {
    checkpoint();
    MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_UINT64_T, MPI_SUM,
                  MPI_COMM_WORLD);
  }

  double maxOnAll(double value) override {
    checkpoint();
    double largest = value;
    MPI_Allreduce(&value, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return largest;
  }

 private:
  int rank_ = 0, size_ = 1;
};

ProcessGroup* openGroup = nullptr;

}  // namespace

std::unique_ptr<ProcessGroup> makeSingleProcessGroup() {
  return std::make_unique<SingleProcess>();
}

bool launchedByMpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

Session::Session(int& argc, char**& argv) {
  if (launchedByMpirun()) {
    MPI_Init(&argc, &argv);
    group_ = std::make_unique<MpiWorld>();
    // Ranks on one machine share its cores (docs/distributed.md, "Threads").
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    int ranksOnThisNode = 1;
    MPI_Comm_size(node, &ranksOnThisNode);
    MPI_Comm_free(&node);
    shareCoresAmong(ranksOnThisNode);
  } else {
    group_ = makeSingleProcessGroup();
  }
  openGroup = group_.get();
}

Session::~Session() {
  openGroup = nullptr;
  if (dynamic_cast<MpiWorld*>(group_.get())) MPI_Finalize();
}

ProcessGroup& world() {
  static SingleProcess alone;
  return openGroup ? *openGroup : alone;
}

void failIfAskedForTest(const ProcessGroup& group) {
  const char* value = std::getenv("PARALLAX_TEST_FAIL_RANK");
  if (!value || std::atoi(value) != group.rank() || *value == '\0') return;
  throw InputError("PARALLAX_TEST_FAIL_RANK", "",
                   "rank " + std::to_string(group.rank()) + " was asked to fail (a test)");
}

}  // namespace parallax::cluster
