#include "parallel/mpi/exchange.hpp"

#include <fmt/format.h>

#include <climits>
#include <cstdint>

#include "core/error.hpp"

namespace cgdem::parallel {

void check_mpi(int rc, const char* call, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw Error(fmt::format("{}: {} failed: {}", what, call, std::string(text, len)));
}

void raise_together(MPI_Comm comm, int rank, const std::string& error, const char* what) {
  const int mine = error.empty() ? INT_MAX : rank;
  int first = INT_MAX;
  check_mpi(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm), "MPI_Allreduce", what);
  if (first == INT_MAX) return;
  if (!error.empty()) throw RaisedTogether(error, true);
  throw RaisedTogether(
      fmt::format("{} stopped on every rank: rank {} found an error (its message is in its output)", what, first),
      false);
}

std::string oversized(const std::vector<Buffer>& out, const std::vector<int>& nb, const char* what) {
  for (size_t k = 0; k < out.size(); ++k)
    if (out[k].size() > static_cast<size_t>(INT_MAX))
      return fmt::format("{}: {} bytes for rank {} exceed an MPI message (int count)", what, out[k].size(), nb[k]);
  return {};
}

std::vector<Buffer> exchange_buffers(MPI_Comm comm, const std::vector<int>& nb, const std::vector<Buffer>& out,
                                     int size_tag, int buffer_tag, const char* what) {
  const int n = static_cast<int>(nb.size());
  std::vector<MPI_Request> req(2 * n);
  std::vector<uint64_t> send_bytes(n), recv_bytes(n);
  for (int k = 0; k < n; ++k) {
    send_bytes[k] = out[k].size();
    check_mpi(MPI_Irecv(&recv_bytes[k], 1, MPI_UINT64_T, nb[k], size_tag, comm, &req[k]), "MPI_Irecv", what);
    check_mpi(MPI_Isend(&send_bytes[k], 1, MPI_UINT64_T, nb[k], size_tag, comm, &req[n + k]), "MPI_Isend", what);
  }
  check_mpi(MPI_Waitall(2 * n, req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall", what);
  std::vector<Buffer> in(n);
  for (int k = 0; k < n; ++k) {
    in[k].resize(recv_bytes[k]);  // at most INT_MAX: its sender checked
    check_mpi(MPI_Irecv(in[k].data(), static_cast<int>(recv_bytes[k]), MPI_BYTE, nb[k], buffer_tag, comm, &req[k]),
              "MPI_Irecv", what);
    check_mpi(MPI_Isend(out[k].data(), static_cast<int>(send_bytes[k]), MPI_BYTE, nb[k], buffer_tag, comm,
                        &req[n + k]),
              "MPI_Isend", what);
  }
  check_mpi(MPI_Waitall(2 * n, req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall", what);
  return in;
}

}  // namespace cgdem::parallel
