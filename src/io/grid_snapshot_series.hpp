// GridSnapshotSeries: cell-centred fields on a uniform Cartesian mesh over time (air phase),
// one HDF5 file per output step plus an XDMF index that ParaView opens directly.
//
// Mesh: nx*ny*nz cells of size spacing = (dx,dy,dz), lower corner at origin (m). Cell
// (i,j,k) has flat index c = i + nx*(j + ny*k) (x fastest) in every field array.
//   <dir>/<prefix>_<step:06>.h5  /grid/n int64[3] = (nx,ny,nz), /grid/origin, /grid/spacing
//                                float64[3] (x,y,z order); /cells/<name> float64 [nz][ny][nx]
//                                for scalars, [nz][ny][nx][3] for vectors (components x,y,z);
//                                every dataset with "units" and "description" (the cell
//                                fields' from write()'s `info`, else from air_field_info());
//                                attributes on "/": series attributes + "description" +
//                                "time" + "time_units" ("s") + "step"; the cell fields
//                                chunked (whole z-planes) and compressed at the series' level
//   <dir>/<prefix>.xdmf          XDMF 3 temporal collection, 3DCoRectMesh topology with
//                                (nz+1, ny+1, nx+1) nodes, ORIGIN_DXDYDZ geometry (XDMF lists
//                                both triples slowest axis first: z, y, x), Center="Cell"
//                                attributes.
// Atomic writes and restart behaviour as SnapshotSeries.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "io/h5_series.hpp"
#include "io/particle_h5.hpp"

namespace cgdem::io {

using CellScalars = std::map<std::string, std::vector<double>>;
using CellVectors = std::map<std::string, std::array<std::vector<double>, 3>>;  // x,y,z components

// Units and description of the cell fields cgdem's air snapshots hold (eps, p, alpha, u:
// app/run_schedule.cpp), used for a field that write() is given no info for; nullptr for
// any other name.
const FieldInfo* air_field_info(const std::string& name);

class GridSnapshotSeries : public H5Series {
 public:
  // compression: 0..9 (h5_options.hpp).
  GridSnapshotSeries(std::string dir, std::string prefix, Attributes attributes, bool resume = false,
                     int compression = kDefaultCompression);

  // Every array has nx*ny*nz values; names must be distinct across scalars and vectors, and
  // each must have its units and description in `info` or in air_field_info().
  std::string write(int64_t step, double time, int nx, int ny, int nz, Vec3 origin, Vec3 spacing,
                    const CellScalars& scalars, const CellVectors& vectors = {}, const FieldInfos& info = {});

 private:
  struct Entry {
    int64_t step = 0;
    double time = 0;
    std::array<int64_t, 3> n{};
    Vec3 origin, spacing;
    std::vector<std::string> scalars, vectors;
  };
  std::string render(const Entry& e) const;
  Entry read_entry(int64_t step) const;
};

}  // namespace cgdem::io
