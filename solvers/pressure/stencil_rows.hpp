// The neighbour rows of one x-row of a 7-point stencil (Poisson7 in double, Stencil32 in
// float): cells are numbered c = i + nx (j + ny k); the x values of row (j, k) start at xr;
// the y-face weights are stored per (i, j, k) with ny + 1 faces in y, the z-face weights per
// (i, j, k) with the top faces of plane nz-1 at the planes' end. A periodic axis (py, pz)
// wraps to the opposite row with the wrap face's weight (face 0); a missing neighbour points
// at the own row, where the caller's face weight is zero. Pointers only: no arithmetic on
// values, so the callers' sums are exactly as they were written out in each.
#pragma once

namespace cgdem::pressure {

template <class T>
struct RowNeighbours {
  const T *xs, *xn, *xb, *xt;  // x of the rows south (j-1), north (j+1), below (k-1), above (k+1)
  const T *ws, *wn, *wb, *wt;  // the weights of the faces between them and the row
};

template <class T>
inline RowNeighbours<T> row_neighbours(const T* xr, const T* wy, const T* wz, int nx, int ny, int nz, int j, int k,
                                       bool py, bool pz) {
  const long plane = long(nx) * ny;
  const long c0 = long(nx) * (j + long(ny) * k);
  RowNeighbours<T> r;
  r.xs = (j > 0) ? xr - nx : (py ? xr + long(nx) * (ny - 1) : xr);
  r.xn = (j < ny - 1) ? xr + nx : (py ? xr - long(nx) * (ny - 1) : xr);
  r.ws = wy + long(nx) * (j + long(ny + 1) * k);
  r.wn = wy + long(nx) * ((j == ny - 1 && py ? 0 : j + 1) + long(ny + 1) * k);
  r.xb = (k > 0) ? xr - plane : (pz ? xr + plane * (nz - 1) : xr);
  r.xt = (k < nz - 1) ? xr + plane : (pz ? xr - plane * (nz - 1) : xr);
  r.wb = wz + c0;
  r.wt = wz + (k == nz - 1 && pz ? long(nx) * j : c0 + plane);
  return r;
}

}  // namespace cgdem::pressure
