/**
 * @file
 * An MPI profiling-interface (PMPI) library that counts what a run sends:
 * calls and bytes per MPI function, per rank. Load it into any MPI program
 * with LD_PRELOAD (benchmarks/dda-scaling/mpi_volume.py does) and set
 * ROCKDDA_MPI_COUNT=PREFIX: at MPI_Finalize every rank writes
 * PREFIX.RANK.csv with the columns function, calls, bytes_sent,
 * bytes_received. The counts are of the calls the program (rockdda,
 * Trilinos, deal.II) makes through the MPI C interface; what the MPI
 * library does inside a collective (its algorithm's own messages) is not
 * counted: a collective's bytes are the payload the rank passes in and gets
 * out.
 *
 * Point-to-point: bytes_sent of MPI_Send/Isend/... (count x type size),
 * bytes_received of MPI_Recv/Irecv as posted (the buffer's capacity, an
 * upper bound; Trilinos posts exact sizes). Collectives: bytes_sent is the
 * rank's contribution, bytes_received what it gets (for MPI_Allreduce both
 * are the vector's size).
 */
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mpi.h>
#include <string>

namespace
{
  /// Totals of one MPI function on this rank.
  struct Count
  {
    unsigned long long calls = 0, sent = 0, received = 0;
  };

  std::map<std::string, Count> &
  counts()
  {
    static std::map<std::string, Count> c;
    return c;
  }

  unsigned long long
  bytes(const int count, MPI_Datatype type)
  {
    int size = 0;
    if (type == MPI_DATATYPE_NULL || count <= 0)
      return 0;
    PMPI_Type_size(type, &size);
    return static_cast<unsigned long long>(count) * size;
  }

  int
  comm_size(MPI_Comm comm)
  {
    int n = 1;
    PMPI_Comm_size(comm, &n);
    return n;
  }

  void
  add(const char              *name,
      const unsigned long long sent,
      const unsigned long long received)
  {
    Count &c = counts()[name];
    ++c.calls;
    c.sent += sent;
    c.received += received;
  }

  unsigned long long
  sum_bytes(const int *counts_in, MPI_Datatype type, MPI_Comm comm)
  {
    unsigned long long s = 0;
    const int          n = comm_size(comm);
    for (int r = 0; r < n; ++r)
      s += bytes(counts_in[r], type);
    return s;
  }
} // namespace

// The sends differ only in their name: one definition each from a macro
// (blocking, then non-blocking).
#define ROCKDDA_COUNTED_SEND(NAME)                     \
  int NAME(const void  *buf,                           \
           int          count,                         \
           MPI_Datatype type,                          \
           int          dest,                          \
           int          tag,                           \
           MPI_Comm     comm)                          \
  {                                                    \
    add(#NAME, bytes(count, type), 0);                 \
    return P##NAME(buf, count, type, dest, tag, comm); \
  }
#define ROCKDDA_COUNTED_ISEND(NAME)                             \
  int NAME(const void  *buf,                                    \
           int          count,                                  \
           MPI_Datatype type,                                   \
           int          dest,                                   \
           int          tag,                                    \
           MPI_Comm     comm,                                   \
           MPI_Request *request)                                \
  {                                                             \
    add(#NAME, bytes(count, type), 0);                          \
    return P##NAME(buf, count, type, dest, tag, comm, request); \
  }

// Reductions that give every rank (or a prefix of) the result.
#define ROCKDDA_COUNTED_REDUCTION(NAME)                      \
  int NAME(const void  *sendbuf,                             \
           void        *recvbuf,                             \
           int          count,                               \
           MPI_Datatype type,                                \
           MPI_Op       op,                                  \
           MPI_Comm     comm)                                \
  {                                                          \
    add(#NAME, bytes(count, type), bytes(count, type));      \
    return P##NAME(sendbuf, recvbuf, count, type, op, comm); \
  }

extern "C" {
ROCKDDA_COUNTED_SEND(MPI_Send)
ROCKDDA_COUNTED_SEND(MPI_Ssend)
ROCKDDA_COUNTED_SEND(MPI_Rsend)
ROCKDDA_COUNTED_ISEND(MPI_Isend)
ROCKDDA_COUNTED_ISEND(MPI_Irsend)
ROCKDDA_COUNTED_ISEND(MPI_Issend)

int
MPI_Recv(void        *buf,
         int          count,
         MPI_Datatype type,
         int          source,
         int          tag,
         MPI_Comm     comm,
         MPI_Status  *status)
{
  add("MPI_Recv", 0, bytes(count, type));
  return PMPI_Recv(buf, count, type, source, tag, comm, status);
}

int
MPI_Irecv(void        *buf,
          int          count,
          MPI_Datatype type,
          int          source,
          int          tag,
          MPI_Comm     comm,
          MPI_Request *request)
{
  add("MPI_Irecv", 0, bytes(count, type));
  return PMPI_Irecv(buf, count, type, source, tag, comm, request);
}

int
MPI_Sendrecv(const void  *sendbuf,
             int          sendcount,
             MPI_Datatype sendtype,
             int          dest,
             int          sendtag,
             void        *recvbuf,
             int          recvcount,
             MPI_Datatype recvtype,
             int          source,
             int          recvtag,
             MPI_Comm     comm,
             MPI_Status  *status)
{
  add("MPI_Sendrecv", bytes(sendcount, sendtype), bytes(recvcount, recvtype));
  return PMPI_Sendrecv(sendbuf,
                       sendcount,
                       sendtype,
                       dest,
                       sendtag,
                       recvbuf,
                       recvcount,
                       recvtype,
                       source,
                       recvtag,
                       comm,
                       status);
}

ROCKDDA_COUNTED_REDUCTION(MPI_Allreduce)

int
MPI_Reduce(const void  *sendbuf,
           void        *recvbuf,
           int          count,
           MPI_Datatype type,
           MPI_Op       op,
           int          root,
           MPI_Comm     comm)
{
  add("MPI_Reduce", bytes(count, type), 0);
  return PMPI_Reduce(sendbuf, recvbuf, count, type, op, root, comm);
}

int
MPI_Bcast(void *buf, int count, MPI_Datatype type, int root, MPI_Comm comm)
{
  add("MPI_Bcast", bytes(count, type), bytes(count, type));
  return PMPI_Bcast(buf, count, type, root, comm);
}

int
MPI_Barrier(MPI_Comm comm)
{
  add("MPI_Barrier", 0, 0);
  return PMPI_Barrier(comm);
}

ROCKDDA_COUNTED_REDUCTION(MPI_Scan)

ROCKDDA_COUNTED_REDUCTION(MPI_Exscan)

int
MPI_Allgather(const void  *sendbuf,
              int          sendcount,
              MPI_Datatype sendtype,
              void        *recvbuf,
              int          recvcount,
              MPI_Datatype recvtype,
              MPI_Comm     comm)
{
  add("MPI_Allgather",
      bytes(sendcount, sendtype),
      bytes(recvcount, recvtype) * comm_size(comm));
  return PMPI_Allgather(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
}

int
MPI_Allgatherv(const void  *sendbuf,
               int          sendcount,
               MPI_Datatype sendtype,
               void        *recvbuf,
               const int   *recvcounts,
               const int   *displs,
               MPI_Datatype recvtype,
               MPI_Comm     comm)
{
  add("MPI_Allgatherv",
      bytes(sendcount, sendtype),
      sum_bytes(recvcounts, recvtype, comm));
  return PMPI_Allgatherv(
    sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm);
}

int
MPI_Gather(const void  *sendbuf,
           int          sendcount,
           MPI_Datatype sendtype,
           void        *recvbuf,
           int          recvcount,
           MPI_Datatype recvtype,
           int          root,
           MPI_Comm     comm)
{
  add("MPI_Gather", bytes(sendcount, sendtype), 0);
  return PMPI_Gather(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
}

int
MPI_Gatherv(const void  *sendbuf,
            int          sendcount,
            MPI_Datatype sendtype,
            void        *recvbuf,
            const int   *recvcounts,
            const int   *displs,
            MPI_Datatype recvtype,
            int          root,
            MPI_Comm     comm)
{
  add("MPI_Gatherv", bytes(sendcount, sendtype), 0);
  return PMPI_Gatherv(sendbuf,
                      sendcount,
                      sendtype,
                      recvbuf,
                      recvcounts,
                      displs,
                      recvtype,
                      root,
                      comm);
}

int
MPI_Alltoall(const void  *sendbuf,
             int          sendcount,
             MPI_Datatype sendtype,
             void        *recvbuf,
             int          recvcount,
             MPI_Datatype recvtype,
             MPI_Comm     comm)
{
  const int n = comm_size(comm);
  add("MPI_Alltoall",
      bytes(sendcount, sendtype) * n,
      bytes(recvcount, recvtype) * n);
  return PMPI_Alltoall(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
}

int
MPI_Alltoallv(const void  *sendbuf,
              const int   *sendcounts,
              const int   *sdispls,
              MPI_Datatype sendtype,
              void        *recvbuf,
              const int   *recvcounts,
              const int   *rdispls,
              MPI_Datatype recvtype,
              MPI_Comm     comm)
{
  add("MPI_Alltoallv",
      sum_bytes(sendcounts, sendtype, comm),
      sum_bytes(recvcounts, recvtype, comm));
  return PMPI_Alltoallv(sendbuf,
                        sendcounts,
                        sdispls,
                        sendtype,
                        recvbuf,
                        recvcounts,
                        rdispls,
                        recvtype,
                        comm);
}

int
MPI_Finalize()
{
  const char *prefix = std::getenv("ROCKDDA_MPI_COUNT");
  if (prefix != nullptr)
    {
      int rank = 0;
      PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
      const std::string name
        = std::string(prefix) + "." + std::to_string(rank) + ".csv";
      if (FILE *f = std::fopen(name.c_str(), "w"))
        {
          std::fprintf(f, "function,calls,bytes_sent,bytes_received\n");
          for (const auto &[function, c] : counts())
            std::fprintf(f,
                         "%s,%llu,%llu,%llu\n",
                         function.c_str(),
                         c.calls,
                         c.sent,
                         c.received);
          std::fclose(f);
        }
    }
  return PMPI_Finalize();
}
}
