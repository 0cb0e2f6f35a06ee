#include "fluid/ibm.hpp"

#include <cmath>

namespace cgdem::fluid {

namespace {

// Fraction inside the walls of the cube of edge dx centred at x; counts sub-sampled boxes.
double box_fraction(const geometry::Scene::Frame& f, const Vec3& x, double dx, int samples, long& sampled) {
  const double h = 0.5 * dx;
  const double pc = f.phi(x);
  const double half_diag = h * std::sqrt(3.0);
  if (pc >= half_diag) return 0.0;
  if (pc <= -half_diag) return 1.0;
  ++sampled;
  return f.solid_fraction(x - Vec3{h, h, h}, x + Vec3{h, h, h}, samples);
}

}  // namespace

bool update_ibm(const MacGrid& g, const geometry::Scene::Frame& frame, int samples, IbmFractions& ibm) {
  if (samples < 1) throw Error("IBM: the number of sub-samples per axis must be >= 1");
  if (ibm.valid && ibm.offsets == frame.offset) return false;
  for (int d = 0; d < 3; ++d) {
    ibm.alpha_face[d] = make_face_field(g, d);
    ibm.ub_face[d] = make_face_field(g, d);
  }
  ibm.alpha_cell = make_cell_field(g);
  ibm.offsets = frame.offset;
  ibm.valid = true;
  ibm.any_solid = false;
  ibm.sampled_faces = 0;
  if (frame.scene == nullptr || frame.scene->empty()) return true;

  long sampled = 0;
  bool any = false;
  for (int d = -1; d < 3; ++d) {  // d = -1: cells
    Field& a = d < 0 ? ibm.alpha_cell : ibm.alpha_face[d];
    std::array<int, 3> e = a.extent();
#pragma omp parallel for schedule(dynamic) if (g.cells() > kOmpMinWork) reduction(+ : sampled) reduction(|| : any)
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          Vec3 x = d < 0 ? g.cell_centre(i, j, k) : g.face_centre(d, i, j, k);
          double al = box_fraction(frame, x, g.dx, samples, sampled);
          a(i, j, k) = al;
          if (al > 0) {
            any = true;
            if (d >= 0) ibm.ub_face[d](i, j, k) = frame.wall_velocity(x)[d];
          }
        }
  }
  ibm.any_solid = any;
  ibm.sampled_faces = sampled;
  return true;
}

}  // namespace cgdem::fluid
