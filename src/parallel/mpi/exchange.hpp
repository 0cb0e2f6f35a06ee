// What the MPI layer's exchanges share (issue 6): MPI error codes turned into
// cgdem::Error, errors raised on every rank together, and the exchange of one byte buffer
// with each neighbour (migration, ghost parcels).
#pragma once
#include <mpi.h>

#include <string>
#include <vector>

#include "parallel/migration.hpp"

namespace cgdem::parallel {

// Throws cgdem::Error "<what>: <call> failed: <MPI's text>" unless rc is MPI_SUCCESS.
void check_mpi(int rc, const char* call, const char* what);

// Collective. Returns when no rank has an error (error empty everywhere); otherwise throws
// on every rank: the rank with the lowest number among those that found one throws its
// message, every other rank an Error "<what> stopped on every rank: rank R found an error
// ...". No rank is then left waiting in a later collective call.
void raise_together(MPI_Comm comm, int rank, const std::string& error, const char* what);

// A message for the first buffer too large for one MPI message (int count), or "".
std::string oversized(const std::vector<Buffer>& out, const std::vector<int>& nb, const char* what);

// Sends out[k] to rank nb[k] and returns what nb[k] sent this rank, for every k: first one
// message of the size with each neighbour, then the buffers (non-blocking, then wait for
// all). Every neighbour must call it with this rank in its list, even with empty buffers.
// Buffers must fit an MPI message (oversized() first, raised together).
std::vector<Buffer> exchange_buffers(MPI_Comm comm, const std::vector<int>& nb, const std::vector<Buffer>& out,
                                     int size_tag, int buffer_tag, const char* what);

}  // namespace cgdem::parallel
