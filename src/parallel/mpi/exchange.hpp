// What the MPI layer's exchanges share (issue 6): MPI error codes turned into
// cgdem::Error, errors raised on every rank together, and the exchange of one byte buffer
// with each neighbour (migration, ghost parcels).
#pragma once
#include <mpi.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "parallel/migration.hpp"

namespace cgdem::parallel {

// Throws cgdem::Error "<what>: <call> failed: <MPI's text>" unless rc is MPI_SUCCESS.
void check_mpi(int rc, const char* call, const char* what);

// An error that every rank of a communicator throws at the same point (raise_together):
// a caller may then stop every rank cleanly, with no rank left in a collective call.
// found_here: this rank found it (its message is the error itself); on the others the
// message names the rank that did.
struct RaisedTogether : Error {
  RaisedTogether(const std::string& message, bool found) : Error(message), found_here(found) {}
  bool found_here;
};

// Collective. Returns when no rank has an error (error empty everywhere); otherwise throws
// RaisedTogether on every rank: each rank that found one throws its own message, every
// other rank "<what> stopped on every rank: rank R found an error ..." (R the lowest of
// those that found one). No rank is then left waiting in a later collective call.
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
