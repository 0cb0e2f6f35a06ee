// Disjoint sets over indices 0..n-1 held in a parent array (parent[i] = i for a root), with
// path halving, for labelling the connected parts of a grid (the floating components of a
// singular Poisson problem: poisson7.cpp, and across ranks solvers/pressure_mpi/dist_poisson.cpp).
// The smaller index becomes the root, so the labels do not depend on the order of unite().
#pragma once
#include <type_traits>
#include <vector>

namespace cgdem::pressure {

template <class I>
I find_root(std::vector<I>& parent, std::type_identity_t<I> c) {
  while (parent[c] != c) {
    parent[c] = parent[parent[c]];
    c = parent[c];
  }
  return c;
}

template <class I>
void unite(std::vector<I>& parent, std::type_identity_t<I> a, std::type_identity_t<I> b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a != b) parent[a < b ? b : a] = a < b ? a : b;
}

}  // namespace cgdem::pressure
