#include "sweep/mpi_work.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef SNAPJUMP_HAVE_MPI
#include <mpi.h>
#endif

namespace snapjump::sweep {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"}) {
    if (std::getenv(v) != nullptr) return true;
  }
  return false;
}

#ifdef SNAPJUMP_HAVE_MPI

bool mpi_available() { return true; }

struct MpiWork::Impl {
  int rank = 0, size = 1;
  MPI_Win win = MPI_WIN_NULL;
  std::int64_t* counter = nullptr;
};

MpiWork::MpiWork() : impl_(std::make_unique<Impl>()) {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &impl_->rank);
  MPI_Comm_size(MPI_COMM_WORLD, &impl_->size);
  const MPI_Aint bytes = impl_->rank == 0 ? static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0;
  MPI_Win_allocate(bytes, sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &impl_->counter,
                   &impl_->win);
  if (impl_->rank == 0) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, impl_->win);
    *impl_->counter = 0;
    MPI_Win_unlock(0, impl_->win);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

MpiWork::~MpiWork() {
  MPI_Win_free(&impl_->win);
  MPI_Finalize();
}

int MpiWork::rank() const { return impl_->rank; }
int MpiWork::size() const { return impl_->size; }
void MpiWork::barrier() const { MPI_Barrier(MPI_COMM_WORLD); }

void MpiWork::broadcast(std::vector<std::size_t>& list) const {
  unsigned long n = list.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  std::vector<unsigned long> buf(list.begin(), list.end());
  buf.resize(n);
  MPI_Bcast(buf.data(), static_cast<int>(n), MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  list.assign(buf.begin(), buf.end());
}

std::size_t MpiWork::next() const {
  const std::int64_t one = 1;
  std::int64_t got = 0;
  MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, impl_->win);
  MPI_Fetch_and_op(&one, &got, MPI_INT64_T, 0, 0, MPI_SUM, impl_->win);
  MPI_Win_unlock(0, impl_->win);
  return static_cast<std::size_t>(got);
}

void MpiWork::progress() const {
  int flag = 0;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
}

long MpiWork::sum(long v) const {
  long s = 0;
  MPI_Allreduce(&v, &s, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return s;
}

bool MpiWork::all(bool ok) const {
  int in = ok ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return out == 1;
}

#else

bool mpi_available() { return false; }

struct MpiWork::Impl {};

MpiWork::MpiWork() {
  throw std::runtime_error(
      "this snapjump was built without MPI (install libopenmpi-dev and rebuild) but was started "
      "by an MPI launcher");
}
MpiWork::~MpiWork() = default;
int MpiWork::rank() const { return 0; }
int MpiWork::size() const { return 1; }
void MpiWork::barrier() const {}
void MpiWork::broadcast(std::vector<std::size_t>&) const {}
std::size_t MpiWork::next() const { return 0; }
void MpiWork::progress() const {}
long MpiWork::sum(long v) const { return v; }
bool MpiWork::all(bool ok) const { return ok; }

#endif

}  // namespace snapjump::sweep
