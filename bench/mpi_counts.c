/* Counts the MPI traffic of each rank, through the MPI profiling interface (PMPI): point-to-point
 * messages and bytes sent, the distinct ranks sent to, and collectives by kind (calls and bytes
 * of their send buffers). Nothing else changes: every call goes on to the MPI library.
 *   mpicc -shared -fPIC -O2 -o libmpi_counts.so mpi_counts.c
 *   MPI_COUNTS_DIR=dir mpirun -x LD_PRELOAD=$PWD/libmpi_counts.so -x MPI_COUNTS_DIR -np 4 lmp ...
 * At MPI_Finalize each rank writes one line to dir/counts.<rank> (to stderr without
 * MPI_COUNTS_DIR):  rank R key value key value ..., the messages sent to rank k as to<k> N.
 * Receives are not counted: every message is counted once, by its sender. Open MPI's collectives
 * do not go through MPI_Send, so their traffic is not counted twice. count-messages.sh uses it. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { SEND, ALLREDUCE, BCAST, BARRIER, ALLGATHER, ALLGATHERV, REDUCE, SCAN, EXSCAN, GATHER,
       GATHERV, SCATTER, SCATTERV, ALLTOALL, ALLTOALLV, REDUCE_SCATTER, NKIND };
static const char *name[NKIND] = {"send", "allreduce", "bcast", "barrier", "allgather",
  "allgatherv", "reduce", "scan", "exscan", "gather", "gatherv", "scatter", "scatterv", "alltoall",
  "alltoallv", "reduce_scatter"};
static long long calls[NKIND], bytes[NKIND];
static long long *to_rank;   /* messages sent to each rank (allocated at the first send) */
static int nworld;

static long long size_of(int count, MPI_Datatype t)
{
  int s = 0;
  if (t != MPI_DATATYPE_NULL) PMPI_Type_size(t, &s);
  return (long long)count * s;
}
static void count_send(int count, MPI_Datatype t, int dest)
{
  calls[SEND]++;
  bytes[SEND] += size_of(count, t);
  if (!to_rank) {
    PMPI_Comm_size(MPI_COMM_WORLD, &nworld);
    to_rank = calloc(nworld, sizeof *to_rank);
  }
  /* dest is a rank of the call's communicator: LAMMPS sends in its world (all ranks) */
  if (dest >= 0 && dest < nworld) to_rank[dest]++;
}
static void count(int kind, int n, MPI_Datatype t)
{
  calls[kind]++;
  bytes[kind] += size_of(n, t);
}

int MPI_Send(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c)
{ count_send(n, t, d); return PMPI_Send(b, n, t, d, tag, c); }
int MPI_Ssend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c)
{ count_send(n, t, d); return PMPI_Ssend(b, n, t, d, tag, c); }
int MPI_Rsend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c)
{ count_send(n, t, d); return PMPI_Rsend(b, n, t, d, tag, c); }
int MPI_Isend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c, MPI_Request *r)
{ count_send(n, t, d); return PMPI_Isend(b, n, t, d, tag, c, r); }
int MPI_Irsend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c, MPI_Request *r)
{ count_send(n, t, d); return PMPI_Irsend(b, n, t, d, tag, c, r); }
int MPI_Sendrecv(const void *sb, int sn, MPI_Datatype st, int d, int stag, void *rb, int rn,
                 MPI_Datatype rt, int s, int rtag, MPI_Comm c, MPI_Status *status)
{
  count_send(sn, st, d);
  return PMPI_Sendrecv(sb, sn, st, d, stag, rb, rn, rt, s, rtag, c, status);
}

int MPI_Allreduce(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c)
{ count(ALLREDUCE, n, t); return PMPI_Allreduce(sb, rb, n, t, op, c); }
int MPI_Bcast(void *b, int n, MPI_Datatype t, int root, MPI_Comm c)
{ count(BCAST, n, t); return PMPI_Bcast(b, n, t, root, c); }
int MPI_Barrier(MPI_Comm c)
{ count(BARRIER, 0, MPI_DATATYPE_NULL); return PMPI_Barrier(c); }
int MPI_Allgather(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt,
                  MPI_Comm c)
{ count(ALLGATHER, sn, st); return PMPI_Allgather(sb, sn, st, rb, rn, rt, c); }
int MPI_Allgatherv(const void *sb, int sn, MPI_Datatype st, void *rb, const int *rn,
                   const int *displ, MPI_Datatype rt, MPI_Comm c)
{ count(ALLGATHERV, sn, st); return PMPI_Allgatherv(sb, sn, st, rb, rn, displ, rt, c); }
int MPI_Reduce(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, int root, MPI_Comm c)
{ count(REDUCE, n, t); return PMPI_Reduce(sb, rb, n, t, op, root, c); }
int MPI_Scan(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c)
{ count(SCAN, n, t); return PMPI_Scan(sb, rb, n, t, op, c); }
int MPI_Exscan(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c)
{ count(EXSCAN, n, t); return PMPI_Exscan(sb, rb, n, t, op, c); }
int MPI_Gather(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt,
               int root, MPI_Comm c)
{ count(GATHER, sn, st); return PMPI_Gather(sb, sn, st, rb, rn, rt, root, c); }
int MPI_Gatherv(const void *sb, int sn, MPI_Datatype st, void *rb, const int *rn,
                const int *displ, MPI_Datatype rt, int root, MPI_Comm c)
{ count(GATHERV, sn, st); return PMPI_Gatherv(sb, sn, st, rb, rn, displ, rt, root, c); }
int MPI_Scatter(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt,
                int root, MPI_Comm c)
{ count(SCATTER, rn, rt); return PMPI_Scatter(sb, sn, st, rb, rn, rt, root, c); }
int MPI_Scatterv(const void *sb, const int *sn, const int *displ, MPI_Datatype st, void *rb, int rn,
                 MPI_Datatype rt, int root, MPI_Comm c)
{ count(SCATTERV, rn, rt); return PMPI_Scatterv(sb, sn, displ, st, rb, rn, rt, root, c); }
int MPI_Alltoall(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt,
                 MPI_Comm c)
{ count(ALLTOALL, sn, st); return PMPI_Alltoall(sb, sn, st, rb, rn, rt, c); }
int MPI_Alltoallv(const void *sb, const int *sn, const int *sd, MPI_Datatype st, void *rb,
                  const int *rn, const int *rd, MPI_Datatype rt, MPI_Comm c)
{ count(ALLTOALLV, 0, st); return PMPI_Alltoallv(sb, sn, sd, st, rb, rn, rd, rt, c); }
int MPI_Reduce_scatter(const void *sb, void *rb, const int *rn, MPI_Datatype t, MPI_Op op,
                       MPI_Comm c)
{ count(REDUCE_SCATTER, 0, t); return PMPI_Reduce_scatter(sb, rb, rn, t, op, c); }

int MPI_Finalize(void)
{
  int me;
  PMPI_Comm_rank(MPI_COMM_WORLD, &me);
  PMPI_Comm_size(MPI_COMM_WORLD, &nworld);
  const char *dir = getenv("MPI_COUNTS_DIR");
  FILE *f = stderr;
  char path[4096];
  if (dir && *dir) {
    snprintf(path, sizeof path, "%s/counts.%d", dir, me);
    if (!(f = fopen(path, "w"))) f = stderr;
  }
  fprintf(f, "rank %d", me);
  for (int k = 0; k < NKIND; k++)
    fprintf(f, " %s %lld %s_bytes %lld", name[k], calls[k], name[k], bytes[k]);
  for (int i = 0; i < nworld; i++) fprintf(f, " to%d %lld", i, to_rank ? to_rank[i] : 0);
  fprintf(f, "\n");
  if (f != stderr) fclose(f);
  free(to_rank);
  return PMPI_Finalize();
}
