// The processes of one job (docs/distributed.md): under mpirun, Open MPI's ranks; otherwise this
// process alone, without MPI ever being started, so that a plain run is unchanged. The render
// gives each rank its frames of a sequence, or its bands of one frame, and merges them on rank 0.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

namespace parallax::cluster {

// A rank's failure, as every rank learns it from ProcessGroup::agree.
struct Failure {
  int rank = 0;
  int exitCode = 1;
  std::string message;  // one line, without "error: "
};

// Thrown at a checkpoint when another rank failed: this rank stops too, quietly (the failing
// rank prints its own message), with the failure's exit code.
class PeerFailed : public std::runtime_error {
 public:
  explicit PeerFailed(Failure failure);
  const Failure& failure() const { return failure_; }

 private:
  Failure failure_;
};

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool isRoot() const { return rank() == 0; }

  // Every rank says whether it failed; all learn the failure of the lowest failing rank, or
  // nothing when all succeeded. Collective: every rank calls it the same number of times.
  virtual std::optional<Failure> agree(const std::optional<Failure>& mine) = 0;
  // agree(nothing), throwing PeerFailed when some rank failed. Every collective step below
  // starts with one, so a rank that fails anywhere meets the others at their next step (main
  // calls agree with its failure) and nobody waits forever or writes after a failure.
  void checkpoint();

  // The bitwise OR of every rank's `bytes` into rank 0's (the others' are left as they were):
  // the parts of a split frame, each byte nonzero on at most one rank, merge exactly.
  virtual void mergeToRoot(std::span<uint8_t> bytes) = 0;
  // Every element summed over the ranks, on every rank.
  virtual void sumOnAll(std::span<uint64_t> values) = 0;
  // The largest of the ranks' values, on every rank.
  virtual double maxOnAll(double value) = 0;
};

// Whether this process was started by mpirun (Open MPI or PMIx environment variables): only
// then is MPI started.
bool launchedByMpirun();

// The job's processes for the life of main: MPI_Init when launched by mpirun (else nothing),
// MPI_Finalize at the end.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ProcessGroup& group() { return *group_; }

 private:
  std::unique_ptr<ProcessGroup> group_;
};

// The open session's group; this process alone when no session is open (library tests).
ProcessGroup& world();

// This process alone: rank 0 of 1; merging and sums leave everything as it is.
std::unique_ptr<ProcessGroup> makeSingleProcessGroup();

// For the suite: PARALLAX_TEST_FAIL_RANK=K makes rank K (of any run, mpirun or not) fail here
// with an InputError naming that variable, as a rank that alone meets bad input would.
void failIfAskedForTest(const ProcessGroup& group);

}  // namespace parallax::cluster
